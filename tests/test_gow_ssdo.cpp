// gow-ragnarok's screen-space terms (renderer/techniques/gow_ragnarok/ssdo, ssgi): the sampling
// pattern's CPU mirror (screen_space_pattern.h) against known answers and against the GLSL
// (tests/gow_ss_test.comp); known answers of ssdo and ssgi on the GPU (an open floor is
// unoccluded and lit exactly as the inverse-square law says; a box darkens the floor behind it
// only with ssdo on; nothing on screen to bounce from gives no indirect light), each in both
// forms (ssdo_ssgi, the combined pass, and the separate ssdo and ssgi: option ss_combined);
// culling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space_shared.h"
#include "renderer/techniques/gow_ragnarok/screen_space_pattern.h"
#include "renderer/techniques/technique.h"
#include "tests/gow_ss_test_shared.h"
#include "tests/gow_render.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------- CPU mirror, known answers

// Cosine-weighted: every direction above the surface, unit length, and the mean cosine of the
// set is the cosine-weighted hemisphere's 2/3; turning the pattern keeps each direction's angle
// to the normal.
TEST(GowSsCpu, DirectionsAreCosineWeighted) {
  for (Vec3 n : {Vec3{0, 1, 0}, Vec3{0, 0, -1}, normalize(Vec3{0.3f, -0.5f, 0.8f})}) {
    double mean_cos = 0;
    for (uint32_t i = 0; i < 1024; ++i) {
      const Vec3 d = ss_direction(i, 1024, 0.0f, n), e = ss_direction(i, 1024, 0.37f, n);
      EXPECT_NEAR(length(d), 1.0, 1e-5);
      EXPECT_GT(dot(d, n), 0.0f);
      EXPECT_NEAR(dot(d, n), dot(e, n), 1e-5);
      mean_cos += dot(d, n) / 1024.0;
    }
    EXPECT_NEAR(mean_cos, 2.0 / 3.0, 2e-3);
  }
  // Direction 0 of 1 sits at the rings' middle: r^2 = 1/2, 45 degrees from the normal.
  EXPECT_NEAR(dot(ss_direction(0, 1, 0.0f, {0, 0, 1}), Vec3{0, 0, 1}), std::sqrt(0.5), 1e-6);
}

TEST(GowSsCpu, RotationIsAHashOfPixelAndFrame) {
  const SsRotation a = ss_rotation(1, 7, 10, 20, glsl::kSsStreamSsdo), b = ss_rotation(1, 7, 10, 20, glsl::kSsStreamSsdo);
  EXPECT_EQ(a.turn, b.turn);
  EXPECT_EQ(a.jitter, b.jitter);
  EXPECT_NE(a.turn, ss_rotation(1, 8, 10, 20, glsl::kSsStreamSsdo).turn);
  EXPECT_NE(a.turn, ss_rotation(1, 7, 11, 20, glsl::kSsStreamSsdo).turn);
  EXPECT_NE(a.turn, ss_rotation(1, 7, 10, 20, glsl::kSsStreamSsgi).turn);
  // Uniform over a screen: the mean turn of 64 x 64 pixels is 1/2.
  double mean = 0;
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      const SsRotation r = ss_rotation(3, 0, x, y, glsl::kSsStreamSsgi);
      ASSERT_GE(r.turn, 0.0f);
      ASSERT_LT(r.turn, 1.0f);
      mean += r.turn / 4096.0;
    }
  EXPECT_NEAR(mean, 0.5, 0.02);
}

// ---------------------------------------------------------------- GPU
using test::GpuTest;

class GowSsGpu : public GpuTest {};

TEST_F(GowSsGpu, PatternMatchesCpu) {
  using namespace glsl;
  std::mt19937 rng(17);
  std::uniform_int_distribution<uint32_t> word(0, 0xffffffffu), px(0, 4095), dirs(1, kSsMaxDirections);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<GowSsTestIn> in(2048);
  for (auto& t : in) {
    const uint32_t n = dirs(rng);
    const Vec3 v = normalize(Vec3{g(rng), g(rng), g(rng)});
    t.key = {word(rng), word(rng) % 100000u, px(rng), px(rng)};
    t.index = {word(rng) & 1u ? kSsStreamSsdo : kSsStreamSsgi, word(rng) % n, n, 0};
    t.normal = {v.x, v.y, v.z, 0};
    // The surface encoding's inputs: unit normals, and one in 16 broken (NaN, zero).
    const Vec3 sn = normalize(Vec3{g(rng), g(rng), g(rng)});
    const uint32_t kind = word(rng) % 16u;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    t.surface = kind == 0 ? glsl::vec4{nan, sn.y, sn.z, 0} : kind == 1 ? glsl::vec4{0, 0, 0, 0} : glsl::vec4{sn.x, sn.y, sn.z, 0};
    t.surface.w = 0.01f + 1000.0f * float(word(rng) % 100000u) / 100000.0f;
    t.index.w = word(rng) & 3u;
  }
  const uint32_t count = uint32_t(in.size());
  auto in_buf = gpu().create_buffer(count * sizeof(GowSsTestIn), BufferUsage::storage, "gow_ss_test.in");
  gpu().upload(*in_buf, in.data(), count * sizeof(GowSsTestIn));
  auto out_buf = gpu().create_buffer(count * sizeof(GowSsTestOut), BufferUsage::storage, "gow_ss_test.out");
  ComputePipelineDesc desc{"gow_ss_test.comp",
                           {{kGowSsTestBindIn, DescriptorKind::storage_buffer}, {kGowSsTestBindOut, DescriptorKind::storage_buffer}},
                           16};
  auto pipeline = gpu().compute_pipeline(desc);
  const Bind binds[] = {{kGowSsTestBindIn, in_buf.get()}, {kGowSsTestBindOut, out_buf.get()}};
  const uint32_t push[4] = {count, 0, 0, 0};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, push, sizeof(push));
  cmd->dispatch((count + kGowSsTestGroup - 1) / kGowSsTestGroup);
  gpu().submit(std::move(cmd));
  std::vector<GowSsTestOut> out(count);
  gpu().download(*out_buf, out.data(), count * sizeof(GowSsTestOut));
  double worst = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const auto& t = in[k];
    const SsRotation r = ss_rotation(t.key.x, t.key.y, t.key.z, t.key.w, t.index.x);
    ASSERT_EQ(out[k].rotation.x, r.turn) << k;  // integer hash, exact float conversion
    ASSERT_EQ(out[k].rotation.y, r.jitter) << k;
    const Vec3 d = ss_direction(t.index.y, t.index.z, r.turn, {t.normal.x, t.normal.y, t.normal.z});
    worst = std::max({worst, double(std::fabs(out[k].direction.x - d.x)), double(std::fabs(out[k].direction.y - d.y)),
                      double(std::fabs(out[k].direction.z - d.z))});
  }
  std::printf("gow screen-space pattern: %u samples, max |GPU - CPU| direction component %.3g\n", count, worst);
  EXPECT_LT(worst, 1e-4);

  // The surface encoding: the GPU's words are the CPU's (the normal's 15-bit codes within one
  // step: the octahedral map's division may round differently), and both decode them alike.
  double worst_deg = 0, worst_decode = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const auto& t = in[k];
    const Vec3 n{t.surface.x, t.surface.y, t.surface.z};
    uint32_t cpu[2];
    ss_pack_surface(t.surface.w, n, t.index.w, cpu);
    const uint32_t gpu_words[2] = {out[k].packed.x, out[k].packed.y};
    ASSERT_EQ(gpu_words[0], cpu[0]) << k;
    ASSERT_EQ(gpu_words[1] & 3u, cpu[1] & 3u) << k;
    const int dx = int((gpu_words[1] >> 2u) & 0x7fffu) - int((cpu[1] >> 2u) & 0x7fffu);
    const int dy = int(gpu_words[1] >> 17u) - int(cpu[1] >> 17u);
    ASSERT_LE(std::abs(dx), 1) << k;
    ASSERT_LE(std::abs(dy), 1) << k;
    const SsSurface s = ss_unpack_surface(gpu_words);
    ASSERT_EQ(out[k].packed.z, s.pixel) << k;
    ASSERT_EQ(out[k].packed.w, s.plane ? 1u : 0u) << k;
    ASSERT_EQ(out[k].unpacked.w, s.dist) << k;
    ASSERT_EQ(s.dist, t.surface.w) << k;
    ASSERT_EQ(s.pixel, t.index.w) << k;
    const bool usable = std::isfinite(n.x) && dot(n, n) > 0.25f;
    ASSERT_EQ(s.plane, usable) << k;
    worst_decode = std::max({worst_decode, double(std::fabs(out[k].unpacked.x - s.normal.x)),
                             double(std::fabs(out[k].unpacked.y - s.normal.y)), double(std::fabs(out[k].unpacked.z - s.normal.z))});
    if (usable) worst_deg = std::max(worst_deg, std::acos(std::min(1.0, double(dot(n, s.normal)))) * 180.0 / kPi);
  }
  std::printf("gow ss surfaces: max |GPU - CPU| decoded normal component %.3g, round trip max %.3g deg\n", worst_decode,
              worst_deg);
  EXPECT_LT(worst_decode, 1e-5);
  EXPECT_LT(worst_deg, 0.05);  // 15 bits over the octahedron: 0.034 degrees at most measured (2048 normals)
}

constexpr uint32_t kW = 96, kH = 54;

// A 20 x 20 m grey floor, a point light at `light`, the camera at (0, 2.5, 3) looking at the
// origin; `extra` objects added.
Scene room_scene(Vec3 light, const json& extra = json::array()) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"lights", json::array({{{"type", "point"}, {"position", {light.x, light.y, light.z}}, {"intensity", {2, 2, 2}}}})},
              {"camera", {{"position", {0, 2.5, 3}}, {"target", {0, 0, 0}}, {"fov_y_deg", 60}}}};
  for (auto& o : extra) doc["objects"].push_back(o);
  return parse_scene(doc, "gow-ssdo-test");
}

Settings ss_settings(const std::map<std::string, double>& opts = {}) {
  const Technique& t = find_technique("gow-ragnarok");
  Settings s;
  s.width = kW;
  s.height = kH;
  s = apply_preset(t, "medium", s);
  return apply_options(t, s, opts);
}

using test::render_gow;

// Nothing but the floor on screen: every direction is open (visible fraction 1) and the local
// light is albedo I cos / (pi d^2) at every floor pixel, ssdo on or off.
TEST_F(GowSsGpu, OpenFloorIsUnoccluded) {
  const Vec3 light{0.3f, 1.0f, -0.2f};
  Scene scene = room_scene(light);
  for (double combined : {1.0, 0.0}) {
    for (double on : {1.0, 0.0}) {
      // ss_cone 1: the combined pass writes the debug view only when asked for.
      auto img = render_gow(gpu(), scene, ss_settings({{"ssdo", on}, {"ss_combined", combined}, {"ss_cone", 1}}),
                            {"ssdo_cone", "ssdo_local_light", "gbuffer_position"});
      double worst = 0, lo = 1;
      uint32_t floor_px = 0;
      for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
          if (img["gbuffer_position"].at(x, y, 3) == 0.0f) continue;
          const Vec3 p{img["gbuffer_position"].at(x, y, 0), img["gbuffer_position"].at(x, y, 1),
                       img["gbuffer_position"].at(x, y, 2)};
          const Vec3 d = light - p;
          const double d2 = dot(d, d), c = d.y / std::sqrt(d2);
          const double expect = 0.5 * c / kPi * 2.0 / d2;
          worst = std::max(worst, std::fabs(img["ssdo_local_light"].at(x, y, 0) - expect) / expect);
          lo = std::min(lo, double(img["ssdo_cone"].at(x, y, 3)));
          ++floor_px;
        }
      EXPECT_GT(floor_px, kW * kH / 2);
      EXPECT_EQ(lo, 1.0) << "ssdo " << on << " combined " << combined;
      EXPECT_LT(worst, 1e-3) << "ssdo " << on << " combined " << combined;
    }
  }
}

// A 1 m box on the floor between the light and the floor behind it (seen by the camera, within
// ssdo_radius of the box): ssdo darkens that floor, the open floor far from the box keeps its
// light. ssdo off leaves the light leaking behind the box.
TEST_F(GowSsGpu, BoxOccludesTheFloorBehindIt) {
  json box = {{"name", "box"},
              {"primitive", {{"type", "box"}, {"size", {1.2, 1.0, 0.6}}}},
              {"material", "grey"},
              {"transform", {{"translate", {0, 0.5, 0}}}}};
  // Light low behind the box, away from the camera: the floor on the camera's side is behind
  // the box as the light sees it.
  Scene scene = room_scene({0.0f, 0.6f, -1.5f}, json::array({box}));
  for (double combined : {1.0, 0.0}) {
    double behind[2] = {0, 0}, open[2] = {0, 0};
    for (int on : {0, 1}) {
      auto img = render_gow(gpu(), scene, ss_settings({{"ssdo", on}, {"ss_combined", combined}}),
                            {"ssdo_local_light", "gbuffer_position"});
      uint32_t nb = 0, no = 0;
      for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
          const FloatImage& pos = img["gbuffer_position"];
          if (pos.at(x, y, 3) == 0.0f || pos.at(x, y, 1) > 0.01f) continue;  // floor only
          const float px = pos.at(x, y, 0), pz = pos.at(x, y, 2);
          const float v = img["ssdo_local_light"].at(x, y, 0);
          if (std::fabs(px) < 0.4f && pz > 0.35f && pz < 0.6f) {
            behind[on] += v;
            ++nb;
          } else if (std::fabs(px) > 3.0f) {
            open[on] += v;
            ++no;
          }
        }
      ASSERT_GT(nb, 4u);
      ASSERT_GT(no, 4u);
      behind[on] /= nb;
      open[on] /= no;
    }
    std::printf("ss_combined %g: floor behind the box: ssdo off %.4g, on %.4g; open floor off %.4g, on %.4g\n",
                combined, behind[0], behind[1], open[0], open[1]);
    EXPECT_LT(behind[1], 0.5 * behind[0]);
    EXPECT_NEAR(open[1], open[0], 1e-3 * open[0]);
  }
}

// Nothing on screen to bounce from (an open floor under a constant sky): no indirect light,
// and the output is the direct light.
TEST_F(GowSsGpu, SsgiFindsNothingOnAnOpenFloor) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"sky", {{"type", "constant"}, {"radiance", {1, 1, 1}}}},
              {"camera", {{"position", {0, 2.5, 3}}, {"target", {0, 0, 0}}, {"fov_y_deg", 60}}}};
  Scene scene = parse_scene(doc, "ssgi-open");
  for (double combined : {1.0, 0.0}) {
    auto img = render_gow(gpu(), scene, ss_settings({{"ss_combined", combined}}),
                          {"ssgi_indirect", "gow_direct", "gow_radiance"});
    double hi = 0, diff = 0;
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x)
        for (uint32_t c = 0; c < 3; ++c) {
          hi = std::max(hi, double(img["ssgi_indirect"].at(x, y, c)));
          diff = std::max(diff, double(std::fabs(img["gow_radiance"].at(x, y, c) - img["gow_direct"].at(x, y, c))));
        }
    EXPECT_EQ(hi, 0.0) << "combined " << combined;
    EXPECT_EQ(diff, 0.0) << "combined " << combined;
  }
}

// ssdo runs only where it has work: a scene without local lights culls it (and ssgi reads no
// local light), and so does local_shadows 1 (direct_lighting shadows them by rays). One form
// runs: ss_combined 1 (the default) culls ssdo and ssgi, 0 culls ssdo_ssgi.
TEST(GowSsGraph, SsdoCulledWithoutUnshadowedLocalLights) {
  const Technique& t = find_technique("gow-ragnarok");
  auto plan_of = [&](const Scene& scene, const Settings& s) {
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
    CompileOptions o;
    o.features = scene.features();
    o.outputs = {"gow_radiance"};
    return compile(decls, o);
  };
  auto runs = [](const Plan& plan, const std::string& name, std::string* reason = nullptr) {
    for (auto& pp : plan.passes)
      if (pp.name == name) {
        if (reason) *reason = pp.reason;
        return pp.runs;
      }
    return false;
  };
  Scene lit = room_scene({0, 1, 0});
  const Settings combined = apply_preset(t, "low", Settings{});
  std::string why;
  EXPECT_TRUE(runs(plan_of(lit, combined), "ssdo_ssgi"));
  for (const char* separate : {"ssdo", "ssgi"}) {
    EXPECT_FALSE(runs(plan_of(lit, combined), separate, &why)) << separate;
    EXPECT_EQ(why, "outputs unused") << separate;
  }
  const Settings s = apply_options(t, combined, {{"ss_combined", 0}});
  EXPECT_FALSE(runs(plan_of(lit, s), "ssdo_ssgi"));
  EXPECT_TRUE(runs(plan_of(lit, s), "ssdo"));
  EXPECT_TRUE(runs(plan_of(lit, s), "ssgi"));
  EXPECT_FALSE(runs(plan_of(lit, apply_options(t, s, {{"local_shadows", 1}})), "ssdo", &why));
  EXPECT_EQ(why, "outputs unused");
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {4, 4}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"sky", {{"type", "constant"}, {"radiance", {1, 1, 1}}}}};
  Scene dark = parse_scene(doc, "no-lights");
  EXPECT_FALSE(runs(plan_of(dark, s), "ssdo", &why));
  EXPECT_NE(why.find("local_lights"), std::string::npos) << why;
  EXPECT_TRUE(runs(plan_of(dark, s), "ssgi"));
}

// ssdo_ssgi moves 8 bytes a pixel fewer for its histories in RGBA16F, and writes the debug view
// ssdo_cone only when option ss_cone asks for it (else the plan has no such image).
TEST(GowSsGraph, HalfHistoriesAndTheConeOnlyWhenAskedFor) {
  const Technique& t = find_technique("gow-ragnarok");
  auto plan_of = [&](const Settings& s, std::vector<std::string> outputs) {
    const Scene scene = room_scene({0, 1, 0});
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
    CompileOptions o;
    o.features = scene.features();
    o.outputs = std::move(outputs);
    return compile(decls, o);
  };
  const Settings s = apply_preset(t, "medium", Settings{});
  const Plan plain = plan_of(s, {"gow_radiance", "gow_direct", "ssgi_indirect"});
  EXPECT_EQ(plain.find("ssdo_cone"), nullptr);
  for (const char* history : {"ssgi_indirect", "ssdo_local_light"}) {
    ASSERT_NE(plain.find(history), nullptr) << history;
    EXPECT_EQ(plain.find(history)->desc.format, Format::rgba16_float) << history;
  }
  EXPECT_THROW(plan_of(s, {"gow_radiance", "ssdo_cone"}), GraphError);
  const Plan asked = plan_of(apply_options(t, s, {{"ss_cone", 1}}), {"gow_radiance", "ssdo_cone"});
  ASSERT_NE(asked.find("ssdo_cone"), nullptr);
}

}  // namespace
}  // namespace gib
