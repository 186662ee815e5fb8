// The techniques' attribution stages (Technique::stages, renderer/techniques/stage_oracles.h):
// each oracle writes what it says, and through the graph override the final image holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "harness/attribution/attribute_command.h"
#include "harness/attribution/suite_attribution.h"
#include "harness/case.h"
#include "harness/case_render.h"
#include "renderer/codecs/half.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/codecs/ycocg_sh.h"
#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "renderer/techniques/stage_oracles.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/case_rows.h"
#include "tests/temp_dir.h"

namespace gib {
namespace {

const TechniqueStage& stage(const std::string& name, const std::string& technique = "probe-volume") {
  for (const TechniqueStage& s : find_technique(technique).stages)
    if (s.name == name) return s;
  throw std::runtime_error("no stage " + name);
}

std::vector<float> as_floats(const std::vector<uint8_t>& b) {
  std::vector<float> f(b.size() / 4);
  std::memcpy(f.data(), b.data(), b.size());
  return f;
}

// Every technique that declares stages: 3-6 of them, their passes the technique's in pass order,
// each oracle written after one of its own stage's passes.
TEST(TechniqueStages, StagesCoverThePassesInOrder) {
  size_t with_stages = 0;
  for (const Technique& t : techniques()) {
    if (t.stages.empty()) continue;
    ++with_stages;
    EXPECT_GE(t.stages.size(), 3u) << t.name;
    EXPECT_LE(t.stages.size(), 6u) << t.name;
    size_t last = 0;
    for (const TechniqueStage& s : t.stages) {
      const std::string& first = s.passes.front();
      size_t at = t.passes.size();
      for (size_t i = 0; i < t.passes.size(); ++i)
        if (t.passes[i].name == first) at = i;
      EXPECT_LT(at, t.passes.size()) << t.name << ": " << s.name << ": " << first;
      EXPECT_GE(at, last) << t.name << ": stage " << s.name << " starts before the stage before it";
      last = at;
      for (const std::string& p : s.passes) {
        bool found = false;
        for (const PassEntry& e : t.passes) found |= e.name == p;
        EXPECT_TRUE(found) << t.name << ": " << s.name << ": " << p;
      }
      for (const auto& [resource, pass] : s.after_pass_of) {
        bool found = false;
        for (const PassEntry& e : t.passes) found |= e.name == pass;
        EXPECT_TRUE(found) << t.name << ": " << s.name << ": " << resource << " after " << pass;
      }
      if (s.make) {
        EXPECT_NE(std::find(s.passes.begin(), s.passes.end(), s.after_pass), s.passes.end()) << t.name << ": " << s.name;
        EXPECT_FALSE(s.oracle.empty()) << t.name << ": " << s.name;
      }
    }
  }
  EXPECT_GE(with_stages, 3u);  // probe-volume, radiance-cache, voxel-clipmap
}

TEST(ProbeVolumeStages, DenoiseOracleIsTheSeedMeanOfTheDecodedSh) {
  const codecs::YcocgSh a = {0.5f, 0.1f, -0.2f, 0.05f, 0.02f, -0.01f}, b = {0.25f, -0.1f, 0.1f, 0.0f, -0.02f, 0.03f};
  OracleInputs in;
  for (const codecs::YcocgSh& v : {a, b}) {
    const std::array<uint32_t, 2> w = codecs::pack_ycocg_sh(v);
    std::vector<uint8_t> bytes(8);
    std::memcpy(bytes.data(), w.data(), 8);
    in.seeds.push_back({{"pixel_sh", bytes}});
  }
  const auto out = stage("denoise").make(in);
  const std::vector<float> y = as_floats(out.at("pixel_gi_y")), c = as_floats(out.at("pixel_gi_c"));
  const codecs::YcocgSh da = codecs::unpack_ycocg_sh(codecs::pack_ycocg_sh(a));
  const codecs::YcocgSh db = codecs::unpack_ycocg_sh(codecs::pack_ycocg_sh(b));
  ASSERT_EQ(y.size(), 4u);
  for (int j = 0; j < 4; ++j) EXPECT_FLOAT_EQ(y[j], 0.5f * (da[j] + db[j])) << j;
  EXPECT_FLOAT_EQ(c[0], 0.5f * (da[4] + db[4]));
  EXPECT_FLOAT_EQ(c[1], 0.5f * (da[5] + db[5]));
}

TEST(ProbeVolumeStages, ProbesOracleIsTheSeedMeanOfTheHalfTexels) {
  OracleInputs in;
  for (float base : {1.0f, 3.0f}) {
    std::vector<uint8_t> bytes(4);
    const uint16_t h[2] = {codecs::float_to_half(base), codecs::float_to_half(base + 1.0f)};
    std::memcpy(bytes.data(), h, 4);
    in.seeds.push_back({{"probe_irradiance", bytes}, {"probe_radiance", bytes}});
  }
  const auto out = stage("probes").make(in);
  uint16_t h[2];
  std::memcpy(h, out.at("probe_irradiance").data(), 4);
  EXPECT_EQ(codecs::half_to_float(h[0]), 2.0f);
  EXPECT_EQ(codecs::half_to_float(h[1]), 3.0f);
}

TEST(StageOracles, Rgb9e5MeanIsTheMeanOfTheDecodedTexelsReencoded) {
  OracleInputs in;
  for (float base : {1.0f, 2.0f}) {
    const uint32_t w[2] = {codecs::encode_rgb9e5(base, 0.5f * base, 0.0f), codecs::encode_rgb9e5(4.0f * base, 0.0f, 0.25f)};
    std::vector<uint8_t> bytes(8);
    std::memcpy(bytes.data(), w, 8);
    in.seeds.push_back({{"probe_irradiance", bytes}});
  }
  const std::vector<uint8_t> out = oracles::mean_rgb9e5(in, "probe_irradiance");
  ASSERT_EQ(out.size(), 8u);
  uint32_t w[2];
  std::memcpy(w, out.data(), 8);
  EXPECT_EQ(w[0], codecs::encode_rgb9e5(1.5f, 0.75f, 0.0f));
  EXPECT_EQ(w[1], codecs::encode_rgb9e5(6.0f, 0.0f, 0.25f));
}

TEST(StageOracles, FloatMeanAndSizeMismatch) {
  OracleInputs in;
  in.seeds.push_back({{"irradiance_x", oracles::floats_to_bytes({1.0f, -2.0f})}});
  in.seeds.push_back({{"irradiance_x", oracles::floats_to_bytes({3.0f, 4.0f})}});
  EXPECT_EQ(as_floats(oracles::mean_floats(in, "irradiance_x")), (std::vector<float>{2.0f, 1.0f}));
  in.seeds.push_back({{"irradiance_x", oracles::floats_to_bytes({3.0f})}});
  EXPECT_THROW(oracles::mean_floats(in, "irradiance_x"), std::runtime_error);
  EXPECT_THROW(oracles::mean_floats(in, "irradiance_y"), std::runtime_error);
}

// radiance-cache's denoise oracle writes each gather image's seed mean into the denoiser's
// output of the same channel, every read taken to absolute units by its own pre-exposure P and
// written at the reads' mean P, which it also writes into the exposure buffer (now and prev).
TEST(RadianceCacheStages, DenoiseOracleIsTheMeanAtOneExposure) {
  OracleInputs in;
  const float p[2] = {1.0f, 3.0f};
  for (int s = 0; s < 2; ++s) {
    std::map<std::string, std::vector<uint8_t>> seed;
    float k = 0.0f;
    for (const char* name : {"gather_sh_r", "gather_sh_g", "gather_sh_b", "gather_direct"}) {
      // Absolute value (1 + k) x (1 + s), pre-exposed by this read's P.
      const uint16_t h[4] = {codecs::float_to_half((1.0f + k) * float(1 + s) * p[s]), 0, 0, 0};
      seed[name] = std::vector<uint8_t>(8);
      std::memcpy(seed[name].data(), h, 8);
      k += 1.0f;
    }
    std::vector<float> exposure(glsl::kExposureWords, 0.5f);
    exposure[glsl::kExposureNow] = p[s];
    seed["exposure"] = oracles::floats_to_bytes(exposure);
    in.seeds.push_back(seed);
  }
  const auto out = stage("denoise", "radiance-cache").make(in);
  const std::vector<float> exposure = as_floats(out.at("exposure"));
  EXPECT_EQ(exposure[glsl::kExposureNow], 2.0f);
  EXPECT_EQ(exposure[glsl::kExposurePrev], 2.0f);
  EXPECT_EQ(exposure[glsl::kExposureAverage], 0.5f);
  float k = 0.0f;
  for (const char* name : {"gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"}) {
    uint16_t h;
    std::memcpy(&h, out.at(name).data(), 2);
    EXPECT_FLOAT_EQ(codecs::half_to_float(h), (1.0f + k) * 1.5f * 2.0f) << name;  // mean absolute x P 2
    k += 1.0f;
  }
}

// The exact oracle of the shared composite's input, through the graph override: indirect_diffuse
// becomes the given reference wherever the G-buffer has albedo (composite multiplies the oracle's
// E / pi by it back), for every technique whose last stage writes it; gow-ragnarok's ssgi oracle
// and radiance-cache's upscale oracle write the indirect_diffuse AOV itself, so there it is the
// reference at every pixel (gow-ragnarok's rounded to halves: its ssgi_indirect is an RGBA16F
// history).
class ExactGiOracleGpu : public test::GpuTest {
 protected:
  void check(const std::string& technique, const std::string& stage_name, bool through_albedo = true,
             bool halves = false);
};

TEST_F(ExactGiOracleGpu, ProbeVolumeUpscale) { check("probe-volume", "upscale"); }
TEST_F(ExactGiOracleGpu, RadianceCacheUpscale) { check("radiance-cache", "upscale", false); }
TEST_F(ExactGiOracleGpu, VoxelClipmapShade) { check("voxel-clipmap", "shade"); }
TEST_F(ExactGiOracleGpu, GowRagnarokSsgi) { check("gow-ragnarok", "ssgi", false, true); }

void ExactGiOracleGpu::check(const std::string& technique, const std::string& stage_name, bool through_albedo,
                             bool halves) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/thin-wall-leak-005.json");
  c.width = 32;
  c.height = 18;
  c.frames = 2;
  TechniqueRun run = test::plain_row(c, technique);
  ASSERT_EQ(run.technique, technique);
  ASSERT_EQ(run.compare_aov, "indirect_diffuse");
  run.frames = 2;
  const TechniqueStage& up = stage(stage_name, technique);
  RunHooks reads;
  reads.read = up.seed_reads;
  reads.read.push_back("gbuffer_albedo");
  CaseRender plain = render_case_hooked(gpu(), c, run, "medium", 0, reads);
  OracleInputs in;
  in.width = c.width;
  in.height = c.height;
  in.seeds.push_back(plain.read);
  for (const std::string& name : reads.read) {  // as the harness fills them: every resource read
    const ResolvedResource* res = plain.plan.find(name);
    in.formats[name] = res->desc.format;
    in.extents[name] = {res->width, res->height};
  }
  FloatImage ref(c.width, c.height, 4, 0.0f);
  for (uint32_t y = 0; y < c.height; ++y)
    for (uint32_t x = 0; x < c.width; ++x)
      for (uint32_t ch = 0; ch < 3; ++ch) ref.at(x, y, ch) = 0.01f * float(x + y) + 0.1f * float(ch);
  in.reference["indirect_diffuse"] = ref;
  RunHooks hooks;
  for (auto& [resource, bytes] : up.make(in)) hooks.overrides.push_back({up.after_pass, resource, bytes});
  const CaseRender oracle = render_case_hooked(gpu(), c, run, "medium", 0, hooks);
  ASSERT_EQ(oracle.image.width, c.width);
  const FloatImage albedo = decode_texels(in.formats["gbuffer_albedo"], c.width, c.height, plain.read["gbuffer_albedo"]);
  uint32_t lit = 0;
  for (uint32_t y = 0; y < c.height; ++y)
    for (uint32_t x = 0; x < c.width; ++x)
      for (uint32_t ch = 0; ch < 3; ++ch) {
        const float a = albedo.at(x, y, ch);
        float expected = !through_albedo ? ref.at(x, y, ch) : a > 0.0f ? a * (ref.at(x, y, ch) / a) : 0.0f;
        if (halves) expected = codecs::half_to_float(codecs::float_to_half(expected));
        EXPECT_NEAR(oracle.image.at(x, y, ch), expected, 1e-6f * std::max(1.0f, expected)) << x << "," << y;
        lit += a > 0.0f;
      }
  EXPECT_GT(lit, c.width * c.height);  // most of the image is a surface
  // Without the oracle the image is the technique's own, not the reference.
  double diff = 0;
  for (size_t i = 0; i < plain.image.pixels.size(); ++i) diff += std::abs(plain.image.pixels[i] - oracle.image.pixels[i]);
  EXPECT_GT(diff, 0.0);
}

// A flagged row in the suite: attribute_row writes the JSON and the waterfall and returns the
// summary the report shows; an analytic case needs no reference (the constant value, and
// indirect_diffuse = that value - the technique's own direct); without --attribute the row says
// the attribution was asked for and not run.
class SuiteAttributionGpu : public test::GpuTest {};

TEST_F(SuiteAttributionGpu, FlaggedRowGetsItsWaterfallOrSaysNotRun) {
  test::TempDir dir;
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/white-furnace-closed-box.json");
  c.width = 16;
  c.height = 9;
  c.frames = 3;
  c.convergence.reset();
  size_t index = c.techniques.size();
  for (size_t i = 0; i < c.techniques.size(); ++i)
    if (c.techniques[i].technique == "radiance-cache" && c.techniques[i].label.empty()) index = i;
  ASSERT_LT(index, c.techniques.size());
  c.techniques[index].attribute = true;
  SuiteOptions o;
  o.out = dir.str();
  o.goldens_dir = dir.str() + "/goldens";
  AttributionSettings st;
  st.seeds = 1;
  st.oracle_seeds = 1;
  st.oracle_frames = 2;
  const nlohmann::json summary = attribute_row(gpu(), c, Tier::ci, c.techniques[index], "low", st, o, false);
  EXPECT_EQ(summary["page"], "attribution/white-furnace-closed-box.radiance-cache.low.html");
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "attribution/white-furnace-closed-box.radiance-cache.low.json"));
  EXPECT_EQ(summary["stages_in_game"], (nlohmann::json{"irradiance_volumes", "denoise", "upscale"}));
  ASSERT_EQ(summary["rois"].size(), 2u);  // the image and the case's one ROI
  EXPECT_EQ(summary["rois"][1]["roi"], "walls");
  EXPECT_GE(summary["rois"][0]["mse"].get<double>(), 0.0);

  PlannedRow p;
  p.key = "white-furnace-closed-box/radiance-cache.low";
  p.kind = "technique";
  p.run_index = index;
  p.technique = "radiance-cache";
  p.preset = "low";
  std::vector<nlohmann::json> rows = {{{"case", "white-furnace-closed-box"}, {"technique", "radiance-cache"},
                                       {"preset", "low"}, {"kind", "technique"}}};
  ASSERT_EQ(row_key_of(rows[0]), p.key);
  attribute_flagged_rows(o, Tier::ci, {c}, {p}, rows);  // o.attribute false
  EXPECT_TRUE(rows[0]["attribution"].contains("not_run")) << rows[0].dump();
}

}  // namespace
}  // namespace gib
