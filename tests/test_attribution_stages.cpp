// probe-volume's attribution stages (renderer/techniques/probe_volume/probe_volume_stages.h):
// each oracle writes what it says, and through the graph override the final image holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "harness/case.h"
#include "harness/case_render.h"
#include "renderer/codecs/half.h"
#include "renderer/codecs/ycocg_sh.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

const TechniqueStage& stage(const std::string& name) {
  for (const TechniqueStage& s : find_technique("probe-volume").stages)
    if (s.name == name) return s;
  throw std::runtime_error("no stage " + name);
}

std::vector<float> as_floats(const std::vector<uint8_t>& b) {
  std::vector<float> f(b.size() / 4);
  std::memcpy(f.data(), b.data(), b.size());
  return f;
}

TEST(ProbeVolumeStages, StagesCoverThePassesInOrder) {
  const Technique& t = find_technique("probe-volume");
  ASSERT_GE(t.stages.size(), 3u);
  ASSERT_LE(t.stages.size(), 6u);
  for (const TechniqueStage& s : t.stages) {
    for (const std::string& p : s.passes) {
      bool found = false;
      for (const PassEntry& e : t.passes) found |= e.name == p;
      EXPECT_TRUE(found) << s.name << ": " << p;
    }
    if (s.make) {
      EXPECT_NE(std::find(s.passes.begin(), s.passes.end(), s.after_pass), s.passes.end()) << s.name;
    }
  }
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

class ProbeVolumeOracleGpu : public test::GpuTest {};

// The upscale oracle through the graph override: indirect_diffuse becomes the given reference
// wherever the G-buffer has albedo (composite multiplies the oracle's E / pi by it back).
TEST_F(ProbeVolumeOracleGpu, UpscaleOracleGivesTheReferenceIndirect) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/thin-wall-leak-005.json");
  c.width = 32;
  c.height = 18;
  c.frames = 2;
  TechniqueRun run;
  for (const TechniqueRun& r : c.techniques)
    if (r.technique == "probe-volume" && r.label.empty()) run = r;
  run.frames = 2;
  const TechniqueStage& up = stage("upscale");
  RunHooks reads;
  reads.read = up.seed_reads;
  CaseRender plain = render_case_hooked(gpu(), c, run, "medium", 0, reads);
  OracleInputs in;
  in.width = c.width;
  in.height = c.height;
  in.seeds.push_back(plain.read);
  in.formats["gbuffer_albedo"] = plain.plan.find("gbuffer_albedo")->desc.format;
  in.extents["gbuffer_albedo"] = {c.width, c.height};
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
        const float expected = a > 0.0f ? a * (ref.at(x, y, ch) / a) : 0.0f;
        EXPECT_NEAR(oracle.image.at(x, y, ch), expected, 1e-6f * std::max(1.0f, expected)) << x << "," << y;
        lit += a > 0.0f;
      }
  EXPECT_GT(lit, c.width * c.height);  // most of the image is a surface
  // Without the oracle the image is the technique's own, not the reference.
  double diff = 0;
  for (size_t i = 0; i < plain.image.pixels.size(); ++i) diff += std::abs(plain.image.pixels[i] - oracle.image.pixels[i]);
  EXPECT_GT(diff, 0.0);
}

}  // namespace
}  // namespace gib
