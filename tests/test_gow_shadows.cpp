// gow-ragnarok's sun shadows (renderer/techniques/gow_ragnarok/): the CPU mirrors of
// shadow_cascades.glsl against known answers and against the GPU's shadow map; known answers of the
// shadow filters on the GPU (a plane fully lit, fully shadowed, the penumbra width under a
// straight edge for a known sun angular radius and occluder height); the penumbra-width metric.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "metrics/image_metrics.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/passes/shadow_cascades.h"
#include "renderer/techniques/technique.h"
#include "tests/gow_cascade_test_shared.h"
#include "tests/gow_render.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------- CPU mirrors, known answers
TEST(GowShadowCpu, CascadeSplitsKnownAnswers) {
  std::vector<float> uniform = cascade_splits(2, 1.0f, 9.0f, 0.0f);
  EXPECT_FLOAT_EQ(uniform[0], 5.0f);
  EXPECT_FLOAT_EQ(uniform[1], 9.0f);
  std::vector<float> log_splits = cascade_splits(2, 1.0f, 100.0f, 1.0f);
  EXPECT_NEAR(log_splits[0], 10.0f, 1e-4);
  EXPECT_FLOAT_EQ(log_splits[1], 100.0f);
  std::vector<float> half = cascade_splits(2, 1.0f, 100.0f, 0.5f);
  EXPECT_NEAR(half[0], 0.5 * 10.0 + 0.5 * 50.5, 1e-4);
}

// The slice sphere holds the slice's 8 corners, and is tight (some corner lies on it).
TEST(GowShadowCpu, SliceSphereHoldsTheSliceCorners) {
  for (float aspect : {1.0f, 16.0f / 9.0f}) {
    for (auto [n, f] : {std::pair{0.05f, 3.0f}, std::pair{3.0f, 10.0f}, std::pair{10.0f, 11.0f}}) {
      const float tan_y = std::tan(30.0f * float(kPi) / 180.0f);
      const Vec2 s = slice_sphere(n, f, tan_y, aspect);
      double worst = 0;
      for (float d : {n, f})
        for (float sx : {-1.0f, 1.0f})
          for (float sy : {-1.0f, 1.0f}) {
            const double x = sx * d * tan_y * aspect, y = sy * d * tan_y, z = d - s.x;
            worst = std::max(worst, std::sqrt(x * x + y * y + z * z));
          }
      EXPECT_LE(worst, s.y * (1 + 1e-5)) << n << ".." << f;
      EXPECT_GE(worst, s.y * (1 - 1e-5)) << n << ".." << f << ": not tight";
    }
  }
}

glsl::ShadowCascadePush test_push(uint32_t cascades, uint32_t res, float distance) {
  GowRagnarokSettings s;
  s.shadow_cascades = cascades;
  s.shadow_resolution = res;
  s.shadow_distance = distance;
  return shadow_cascade_push(s, 0.05f);
}

// Every cascade's square holds its slice's sphere (snapping moves it by under a texel, which
// the two-texel margin covers), and depths of the sphere lie in [0, 1].
TEST(GowShadowCpu, CascadeSquareHoldsItsSphere) {
  const glsl::ShadowCascadePush p = test_push(4, 1024, 40.0f);
  const ShadowCameraCpu cam{{1234.5f, 3.0f, -777.25f}, normalize(Vec3{0.3f, -0.2f, -1.0f}), 0.577f, 16.0f / 9.0f};
  const ShadowBasisCpu b = shadow_basis(normalize(Vec3{0.4f, 1.0f, 0.2f}));
  const float splits[4] = {p.splits.x, p.splits.y, p.splits.z, p.splits.w};
  for (uint32_t i = 0; i < 4; ++i) {
    const ShadowCascadeCpu c = shadow_cascade(i, cam, b, p);
    const Vec2 s = slice_sphere(i ? splits[i - 1] : p.params.w, splits[i], cam.tan_y, cam.aspect);
    const Vec3 centre = cam.forward * s.x;
    for (Vec3 dir : {b.r, b.u, b.s, -b.r, -b.u, -b.s}) {
      const Vec3 q = shadow_project(c, b, centre + dir * s.y);
      EXPECT_GE(std::min(q.x, q.y), 0.0f) << "cascade " << i;
      EXPECT_LE(std::max(q.x, q.y), 1.0f) << "cascade " << i;
      EXPECT_GE(q.z, 0.0f);
      EXPECT_LE(q.z, 1.0f);
    }
    // The sun side is nearer (smaller depth) and the far side farther.
    EXPECT_LT(shadow_project(c, b, centre + b.s).z, shadow_project(c, b, centre - b.s).z);
    // The texel grid is world-fixed: offset + camera coordinate is a whole number of texels.
    const float texel = 2.0f * c.half_extent / p.params.y;
    const double k = (double(c.offset_x) + dot(cam.position, b.r)) / texel;
    EXPECT_NEAR(k, std::round(k), 0.02) << "cascade " << i;
  }
  // Selection: the camera's own position is in cascade 0, a point past the shadow distance in none.
  EXPECT_EQ(select_cascade(cam, b, p, cam.forward * 0.5f, 0.1f, 2.0f), 0u);
  EXPECT_EQ(select_cascade(cam, b, p, cam.forward * 500.0f, 0.1f, 2.0f), glsl::kShadowMaxCascades);
  // A point in the middle of the last slice picks the last cascade or an earlier one that holds it.
  const uint32_t last = select_cascade(cam, b, p, cam.forward * 35.0f, 0.1f, 2.0f);
  EXPECT_LE(last, 3u);
  EXPECT_GE(last, 2u);
}

// The filter disk: inside the unit disk, even area density (the share of taps within radius
// rho is rho^2, to one tap), rotation only turns it.
TEST(GowShadowCpu, DiskTapsHaveEvenAreaDensity) {
  for (uint32_t n : {8u, 16u, 32u}) {
    for (float rho : {0.25f, 0.5f, 0.75f}) {
      uint32_t inside = 0;
      for (uint32_t k = 0; k < n; ++k) {
        Vec2 d = disk_tap(k, n, 0.0f);
        EXPECT_LE(d.x * d.x + d.y * d.y, 1.0f + 1e-6f);
        if (d.x * d.x + d.y * d.y <= rho * rho) ++inside;
      }
      EXPECT_NEAR(double(inside) / n, rho * rho, 1.0 / n + 1e-9) << n << " taps, radius " << rho;
    }
    const Vec2 a = disk_tap(5, n, 0.0f), b = disk_tap(5, n, 1.0f);
    EXPECT_NEAR(a.x * a.x + a.y * a.y, b.x * b.x + b.y * b.y, 1e-6);
    EXPECT_NEAR(std::atan2(b.y, b.x) - std::atan2(a.y, a.x), 1.0, 1e-4);
  }
}

// The filtered tap: a lit/shadowed comparison per texel, bilinearly weighted.
TEST(GowShadowCpu, ShadowTapKnownAnswers) {
  const uint32_t res = 8;
  FloatImage map(res * 2, res, 1, 0.5f);
  for (uint32_t y = 0; y < res; ++y)
    for (uint32_t x = 4; x < res; ++x) map.at(x, y, 0) = 0.2f;  // cascade 0: an occluder over x >= 4
  EXPECT_EQ(shadow_tap(map, 0, 0.5f / res, 0.5f, 0.4f, res), 1.0f);   // in front of the surface: lit
  EXPECT_EQ(shadow_tap(map, 0, 6.5f / res, 0.5f, 0.4f, res), 0.0f);   // behind the occluder
  EXPECT_EQ(shadow_tap(map, 0, 4.0f / res, 0.5f, 0.4f, res), 0.5f);   // halfway between texels 3 and 4
  EXPECT_NEAR(shadow_tap(map, 0, 3.75f / res, 0.5f, 0.4f, res), 0.75f, 1e-6);
  EXPECT_EQ(shadow_tap(map, 1, 6.5f / res, 0.5f, 0.4f, res), 1.0f);   // cascade 1 has no occluder
  EXPECT_EQ(shadow_tap(map, 0, -3.0f, 0.5f, 0.4f, res), 1.0f);        // clamped to its own square
}

// ---------------------------------------------------------------- the penumbra metric
TEST(PenumbraMetric, KnownWidths) {
  // A linear ramp from 0 to 1 over columns 10..30: 10-90 % spans 16 columns, either way round.
  std::vector<double> ramp(40);
  for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = std::clamp((double(i) - 10.0) / 20.0, 0.0, 1.0);
  EXPECT_NEAR(metrics::penumbra_width(ramp, ramp, 0, 1), 16.0, 1e-9);
  std::vector<double> rev(ramp.rbegin(), ramp.rend());
  EXPECT_NEAR(metrics::penumbra_width(rev, rev, 0, 1), 16.0, 1e-9);
  // A hard step: under one column.
  std::vector<double> step(40, 0.0);
  for (size_t i = 20; i < step.size(); ++i) step[i] = 1.0;
  EXPECT_NEAR(metrics::penumbra_width(step, step, 0, 1), 0.8, 1e-9);
  // A leak never gets darker than 0.5 of the levels: no width.
  std::vector<double> leak(40);
  for (size_t i = 0; i < leak.size(); ++i) leak[i] = 0.5 + 0.5 * ramp[i];
  EXPECT_TRUE(std::isinf(metrics::penumbra_width(leak, ramp, 0, 1)));
  // The tail of another edge before the umbra is skipped: the walk starts at the darkest column.
  std::vector<double> tail = ramp;
  tail[0] = 0.3, tail[1] = 0.2;
  EXPECT_NEAR(metrics::penumbra_width(tail, tail, 0, 1), 16.0, 1e-9);
  EXPECT_THROW(metrics::penumbra_width(ramp, ramp, 1, 1), std::invalid_argument);
  EXPECT_THROW(metrics::penumbra_width(ramp, step, 0, std::nan("")), std::invalid_argument);
}

TEST(PenumbraMetric, ImageErrorIsRelativeWidthError) {
  // Reference: ramp over 20 columns (width 16); test: over 40 (width 32): error 1.
  FloatImage ref(64, 4, 3), test(64, 4, 3);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 64; ++x)
      for (uint32_t c = 0; c < 3; ++c) {
        ref.at(x, y, c) = float(std::clamp((double(x) - 20.0) / 20.0, 0.0, 1.0));
        test.at(x, y, c) = float(std::clamp((double(x) - 10.0) / 40.0, 0.0, 1.0));
      }
  EXPECT_NEAR(metrics::penumbra_width_error(ref, test, {}), 1.0, 1e-5);
  EXPECT_NEAR(metrics::penumbra_width_error(ref, ref, {}), 0.0, 1e-12);
  FloatImage flat(64, 4, 3, 1.0f);
  EXPECT_THROW(metrics::penumbra_width_error(flat, ref, {}), std::invalid_argument);
}

// ---------------------------------------------------------------- GPU
using test::GpuTest;
constexpr uint32_t kW = 128, kH = 72;
constexpr float kCamHeight = 0.3f;

// A 20 x 20 m grey floor seen from kCamHeight straight above, under a sun of angular radius
// `radius_deg` from `sun_dir`; `extra` objects added.
Scene shadow_scene(Vec3 sun_dir, float radius_deg, const json& extra = json::array()) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"sun", {{"direction", {sun_dir.x, sun_dir.y, sun_dir.z}}, {"irradiance", {3, 3, 3}},
                       {"angular_radius_deg", radius_deg}}},
              {"camera", {{"position", {0, kCamHeight, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fov_y_deg", 60}}}};
  for (auto& o : extra) doc["objects"].push_back(o);
  return parse_scene(doc, "gow-shadows-test");
}
// A 20 x 20 m quad at height h over x < x_edge (facing down): a straight shadow edge along z.
json half_plane(float h, float x_edge = 0.0f) {
  return {{"name", "occluder"},
          {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "-y"}}},
          {"material", "grey"},
          {"transform", {{"translate", {x_edge - 10.0f, h, 0}}}}};
}

Settings shadow_settings(uint32_t filter, const std::map<std::string, double>& opts = {}) {
  const Technique& t = find_technique("gow-ragnarok");
  Settings s;
  s.width = kW;
  s.height = kH;
  s = apply_preset(t, "medium", s);
  std::map<std::string, double> o = {{"shadow_filter", filter}, {"cascades", 1}, {"shadow_distance", 1.0},
                                     {"shadow_resolution", 2048}};
  for (auto& [k, v] : opts) o[k] = v;
  return apply_options(t, s, o);
}

using test::render_gow;

const char* vis_slot(uint32_t filter) { return filter ? "shadow_contact_hardening" : "shadow_pcf"; }

class GowShadowGpu : public GpuTest {};

// The shadow map holds, per texel, the depth of the floor where the texel's centre projects
// onto it (a sun 45 degrees up, so depth varies over the map): the GPU raster of shadow_cascades.glsl
// against the CPU mirror's cascade and projection.
TEST_F(GowShadowGpu, ShadowMapMatchesCpuProjection) {
  const Vec3 sun = normalize(Vec3{1.0f, 1.0f, 0.3f});
  Scene scene = shadow_scene(sun, 1.0f);
  Settings s = shadow_settings(1, {{"shadow_resolution", 256}});
  FloatImage map = render_gow(gpu(), scene, s, {"shadow_map"})["shadow_map"];
  const glsl::ShadowCascadePush p = shadow_cascade_push(s.params<GowRagnarokSettings>(), scene.camera.near_plane);
  const float tan_y = std::tan(30.0f * float(kPi) / 180.0f);
  const ShadowCameraCpu cam{scene.camera.position, normalize(scene.camera.target - scene.camera.position), tan_y,
                            float(kW) / float(kH)};
  const ShadowBasisCpu b = shadow_basis(sun);
  const ShadowCascadeCpu c = shadow_cascade(0, cam, b, p);
  const uint32_t res = uint32_t(p.params.y);
  ASSERT_EQ(map.width, res);
  double worst = 0;
  uint32_t floor_texels = 0;
  for (uint32_t j = 0; j < res; ++j)
    for (uint32_t i = 0; i < res; ++i) {
      const float lx = ((i + 0.5f) / res - 0.5f) * 2.0f * c.half_extent + c.offset_x;
      const float ly = ((j + 0.5f) / res - 0.5f) * 2.0f * c.half_extent + c.offset_y;
      // Camera-relative point on the texel's line towards the sun, on the floor (y = 0).
      const Vec3 base = b.r * lx + b.u * ly;
      const float t = (-cam.position.y - base.y) / b.s.y;
      const Vec3 x_rel = base + b.s * t;
      const Vec3 world = x_rel + cam.position;
      if (std::fabs(world.x) > 9.5f || std::fabs(world.z) > 9.5f) continue;
      const float expect = shadow_project(c, b, x_rel).z;
      if (expect < 0.0f || expect > 1.0f) continue;
      worst = std::max(worst, double(std::fabs(map.at(i, j, 0) - expect)));
      ++floor_texels;
    }
  std::printf("shadow map vs CPU projection: %u floor texels, max |depth difference| %.3g\n", floor_texels, worst);
  EXPECT_GT(floor_texels, res * res / 2);
  EXPECT_LT(worst, 1e-5);
}

// A plane in the open is lit everywhere (no acne), with the min/max early-out and without it,
// overhead and at a low sun (the receiver-plane slope); its direct light is albedo E cos / pi.
TEST_F(GowShadowGpu, OpenPlaneIsFullyLit) {
  for (Vec3 sun : {Vec3{0, 1, 0}, normalize(Vec3{1.0f, 0.6f, 0.2f})}) {
    Scene scene = shadow_scene(sun, 3.0f);
    for (uint32_t filter : {0u, 1u})
      for (double minmax : {0.0, 1.0}) {
        Settings s = shadow_settings(filter, {{"minmax_early_out", minmax}, {"sky_rays", 0}});
        auto img = render_gow(gpu(), scene, s, {vis_slot(filter), "direct_light"});
        double lo = 1, worst = 0;
        const double expect = 0.5 * 3.0 * sun.y / kPi;
        for (uint32_t y = 0; y < kH; ++y)
          for (uint32_t x = 0; x < kW; ++x) {
            lo = std::min(lo, double(img[vis_slot(filter)].at(x, y, 0)));
            worst = std::max(worst, std::abs(img["direct_light"].at(x, y, 0) - expect) / expect);
          }
        EXPECT_EQ(lo, 1.0) << vis_slot(filter) << " minmax " << minmax << " sun.y " << sun.y;
        EXPECT_LT(worst, 1e-4) << "direct light, " << vis_slot(filter);
      }
  }
}

// Under a roof that covers the whole view every floor pixel is shadowed: exactly 0.
TEST_F(GowShadowGpu, RoofedPlaneIsFullyShadowed) {
  json roof = {{"name", "roof"},
               {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "-y"}}},
               {"material", "grey"},
               {"transform", {{"translate", {0, 0.5, 0}}}}};
  Scene scene = shadow_scene(normalize(Vec3{0.2f, 1.0f, 0.1f}), 3.0f, json::array({roof}));
  for (uint32_t filter : {0u, 1u})
    for (double minmax : {0.0, 1.0}) {
      Settings s = shadow_settings(filter, {{"minmax_early_out", minmax}});
      FloatImage v = render_gow(gpu(), scene, s, {vis_slot(filter)})[vis_slot(filter)];
      double hi = 0;
      for (float x : v.pixels) hi = std::max(hi, double(x));
      EXPECT_EQ(hi, 0.0) << vis_slot(filter) << " minmax " << minmax;
    }
}

// Visibility fraction of a disk cut by a straight edge at signed distance a (in radii) from its
// centre, the disk's part beyond the edge: the 10-90 % width is 2 a10 R with F(a10) = 0.1.
double disk_beyond(double a) { return (std::acos(a) - a * std::sqrt(1 - a * a)) / kPi; }
double a10() {
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i) ((disk_beyond(0.5 * (lo + hi)) > 0.1) ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// 10-90 % width (metres, along x) of a visibility image's mean row, x taken from the G-buffer.
double measured_width(const FloatImage& vis, const FloatImage& pos) {
  std::vector<double> prof(vis.width, 0.0), xs(vis.width, 0.0);
  for (uint32_t x = 0; x < vis.width; ++x) {
    for (uint32_t y = 0; y < vis.height; ++y) {
      prof[x] += vis.at(x, y, 0) / vis.height;
      xs[x] += pos.at(x, y, 0) / vis.height;
    }
  }
  const double cols = metrics::penumbra_width(prof, prof, 0.0, 1.0);
  return cols * (xs.back() - xs.front()) / double(vis.width - 1);
}

// Sun overhead, angular radius 3 degrees, a straight edge 0.5 m above the floor: the true
// penumbra is 2 a10 h tan(3 deg) wide (a disk light cut by a line). Contact hardening with the
// sun-derived radius must match it within its stated quantisation: one march step of the
// occluder height (2 m / 64 steps / 0.5 m = 6.3 %) plus a texel of bilinear footprint each side
// (2 x 1.15 mm / 36 mm = 6.4 %): 15 %. PCF blurs with the full radius (the sun seen from 2 m) at
// every height: its width is 2 a10 (2 m) tan(3 deg), four times the true one.
TEST_F(GowShadowGpu, PenumbraWidthUnderAStraightEdge) {
  const double h = 0.5, tan_t = std::tan(3.0 * kPi / 180.0);
  Scene scene = shadow_scene(Vec3{0, 1, 0}, 3.0f, json::array({half_plane(float(h))}));
  const double truth = 2 * a10() * h * tan_t, pcf_expect = 2 * a10() * 2.0 * tan_t;
  for (uint32_t filter : {0u, 1u}) {
    Settings s = shadow_settings(filter, {{"taps", 32}, {"march_steps", 64}});
    auto img = render_gow(gpu(), scene, s, {vis_slot(filter), "gbuffer_position"});
    const double w = measured_width(img[vis_slot(filter)], img["gbuffer_position"]);
    const double expect = filter ? truth : pcf_expect;
    std::printf("%-26s penumbra 10-90 %% width %.4f m, expected %.4f m (true %.4f m), error %+.1f %%\n",
                vis_slot(filter), w, expect, truth, 100.0 * (w - expect) / expect);
    EXPECT_NEAR(w, expect, 0.15 * expect) << vis_slot(filter);
  }
}

// The negative control of contact-shadows: a bias larger than the occluder's height above the
// floor lights the floor under the edge (the comparison puts the receiver in front of it).
TEST_F(GowShadowGpu, HugeBiasLeaksUnderTheOccluder) {
  Scene scene = shadow_scene(Vec3{0, 1, 0}, 3.0f, json::array({half_plane(0.5f, 0.2f)}));
  for (uint32_t filter : {0u, 1u}) {
    double dark[2];
    for (int leak = 0; leak < 2; ++leak) {
      Settings s = shadow_settings(filter, {{"shadow_bias", leak ? 0.6 : 0.02}});
      FloatImage v = render_gow(gpu(), scene, s, {vis_slot(filter)})[vis_slot(filter)];
      dark[leak] = 0;
      for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW / 4; ++x) dark[leak] += v.at(x, y, 0) / (kH * kW / 4);  // left quarter: x < -0.15 m
    }
    EXPECT_LT(dark[0], 0.01) << vis_slot(filter);
    EXPECT_GT(dark[1], 0.99) << vis_slot(filter);
  }
}

// Scenes with no sun cull every shadow pass, and direct_lighting reads no visibility slot.
TEST(GowShadowGraph, NoSunCullsTheShadowPasses) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {4, 4}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"sky", {{"type", "constant"}, {"radiance", {1, 1, 1}}}}};
  Scene scene = parse_scene(doc, "no-sun");
  const Technique& t = find_technique("gow-ragnarok");
  Settings s = apply_preset(t, "low", Settings{});
  std::vector<PassDecl> decls;
  for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
  CompileOptions o;
  o.features = scene.features();
  o.outputs = {"gow_radiance"};
  Plan plan = compile(decls, o);
  for (auto& pp : plan.passes) {
    const bool shadow = pp.name.rfind("shadow", 0) == 0;
    // ssdo has no local lights either; the separate screen-space passes give way to ssdo_ssgi
    // (test_gow_ssdo.cpp).
    if (pp.name == "ssdo" || pp.name == "ssgi") continue;
    // The reflection passes (no glossy material, and `reflection` not asked for) are culled too,
    // and so is direct_aov (the `direct` AOV, not asked for).
    const bool reflection = pp.name == "cubemap_capture" || pp.name.rfind("reflections_", 0) == 0;
    EXPECT_EQ(pp.runs, !shadow && !reflection && pp.name != "direct_aov") << pp.name << ": " << pp.reason;
  }
  // With a sun, the selected filter runs and the other is culled.
  doc["sun"] = {{"direction", {0, 1, 0}}, {"irradiance", {1, 1, 1}}};
  Scene sunny = parse_scene(doc, "sun");
  for (uint32_t filter : {0u, 1u}) {
    Settings f = apply_options(t, s, {{"shadow_filter", filter}});
    decls.clear();
    for (auto& p : make_passes(t)) decls.push_back(p->declare(sunny, f));
    o.features = sunny.features();
    Plan pl = compile(decls, o);
    for (auto& pp : pl.passes) {
      if (pp.name == "shadows_pcf") {
        EXPECT_EQ(pp.runs, filter == 0);
      } else if (pp.name == "shadows_contact_hardening") {
        EXPECT_EQ(pp.runs, filter == 1);
      } else if (pp.name == "shadow_maps" || pp.name == "shadow_minmax") {
        EXPECT_TRUE(pp.runs);
      }
    }
  }
}

// ---------------------------------------------------------------- cascade seams

// The seam blend weight (shadow_cascades.h): 0 deep inside a cascade, rising monotonically to
// (nearly) 1 where selection passes to the next cascade, so the blended result is continuous
// there; 0 everywhere with the band 0 (the control) and in the last cascade.
TEST(GowShadowCpu, SeamBlendWeightRisesToOneAtTheSeam) {
  glsl::ShadowCascadePush p = test_push(4, 1024, 40.0f);
  ASSERT_FLOAT_EQ(p.blend.x, 0.1f);  // the default band
  const ShadowCameraCpu cam{{3.0f, 2.0f, -5.0f}, normalize(Vec3{0.3f, -0.2f, -1.0f}), 0.577f, 16.0f / 9.0f};
  const ShadowBasisCpu b = shadow_basis(normalize(Vec3{0.4f, 1.0f, 0.2f}));
  const float margin_m = 0.01f, margin_tex = 3.0f;
  uint32_t seams = 0;
  float prev_w = 0;
  uint32_t prev = select_cascade(cam, b, p, cam.forward * 0.1f, margin_m, margin_tex);
  EXPECT_EQ(prev, 0u);
  EXPECT_EQ(cascade_blend_weight(cam, b, p, 0, cam.forward * 0.1f, margin_m, margin_tex), 0.0f);
  for (float t = 0.1f; t < 45.0f; t += 0.001f) {
    const Vec3 x = cam.forward * t;
    const uint32_t i = select_cascade(cam, b, p, x, margin_m, margin_tex);
    if (i == glsl::kShadowMaxCascades) break;
    const float w = cascade_blend_weight(cam, b, p, i, x, margin_m, margin_tex);
    EXPECT_GE(w, 0.0f);
    EXPECT_LE(w, 1.0f);
    if (i != prev) {
      // Selection moved on: just before it the next cascade's weight was (nearly) whole.
      EXPECT_EQ(i, prev + 1);
      EXPECT_GT(prev_w, 0.99f) << "seam " << prev << " -> " << i << " at " << t << " m";
      ++seams;
    } else {
      EXPECT_GE(w, prev_w - 1e-5f) << "weight falls towards the seam at " << t << " m";
    }
    if (i == 3) {
      EXPECT_EQ(w, 0.0f);  // the last cascade has nothing to blend into
    }
    prev = i;
    prev_w = w;
  }
  EXPECT_EQ(seams, 3u);
  // Off: no blend anywhere.
  p.blend.x = 0;
  for (float t = 0.1f; t < 45.0f; t += 0.01f) {
    const Vec3 x = cam.forward * t;
    const uint32_t i = select_cascade(cam, b, p, x, margin_m, margin_tex);
    if (i < glsl::kShadowMaxCascades) {
      EXPECT_EQ(cascade_blend_weight(cam, b, p, i, x, margin_m, margin_tex), 0.0f);
    }
  }
}

// The GPU's selection and blend weight (shadow_cascades.glsl, through tests/gow_cascade_test.comp)
// agree with the CPU mirror on random points in and around four cascades.
class GowCascadeGpu : public GpuTest {};
TEST_F(GowCascadeGpu, SelectionAndSeamBlendMatchTheCpuMirror) {
  const glsl::ShadowCascadePush p = test_push(4, 1024, 40.0f);
  const ShadowCameraCpu cam{{1234.5f, 3.0f, -777.25f}, normalize(Vec3{0.3f, -0.2f, -1.0f}), 0.577f, 16.0f / 9.0f};
  const Vec3 sun = normalize(Vec3{0.4f, 1.0f, 0.2f});
  const ShadowBasisCpu b = shadow_basis(sun);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), dist(0.0f, 50.0f), margin(0.0f, 0.2f);
  std::vector<glsl::GowCascadeTestIn> in(4096);
  for (auto& t : in) {
    const Vec3 x = cam.forward * dist(rng) + Vec3{u(rng), u(rng), u(rng)} * 8.0f;
    t.x_rel = {x.x, x.y, x.z, margin(rng)};
  }
  glsl::GowCascadeTestPush push{};
  push.cascades = p;
  push.camera = {cam.position.x, cam.position.y, cam.position.z, cam.tan_y};
  push.forward = {cam.forward.x, cam.forward.y, cam.forward.z, cam.aspect};
  push.sun = {sun.x, sun.y, sun.z, 0};
  static_assert(sizeof(push) == 128, "GowCascadeTestPush must match tests/gow_cascade_test_shared.h");
  const uint32_t count = uint32_t(in.size());
  auto in_buf = gpu().create_buffer(count * sizeof(glsl::GowCascadeTestIn), BufferUsage::storage, "gow_cascade_test.in");
  gpu().upload(*in_buf, in.data(), count * sizeof(glsl::GowCascadeTestIn));
  auto out_buf = gpu().create_buffer(count * sizeof(glsl::GowCascadeTestOut), BufferUsage::storage, "gow_cascade_test.out");
  ComputePipelineDesc desc{"gow_cascade_test.comp",
                           {{glsl::kGowCascadeTestBindIn, DescriptorKind::storage_buffer},
                            {glsl::kGowCascadeTestBindOut, DescriptorKind::storage_buffer}},
                           sizeof(push)};
  auto pipeline = gpu().compute_pipeline(desc);
  const Bind binds[] = {{glsl::kGowCascadeTestBindIn, in_buf.get()}, {glsl::kGowCascadeTestBindOut, out_buf.get()}};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch((count + glsl::kGowCascadeTestGroup - 1) / glsl::kGowCascadeTestGroup);
  gpu().submit(std::move(cmd));
  std::vector<glsl::GowCascadeTestOut> out(count);
  gpu().download(*out_buf, out.data(), count * sizeof(glsl::GowCascadeTestOut));
  uint32_t differ = 0, blended = 0;
  double worst = 0;
  const float margin_tex = 2.0f + p.area.w;
  for (uint32_t k = 0; k < count; ++k) {
    const Vec3 x{in[k].x_rel.x, in[k].x_rel.y, in[k].x_rel.z};
    const uint32_t i = select_cascade(cam, b, p, x, in[k].x_rel.w, margin_tex);
    if (uint32_t(out[k].result.x) != i) {
      ++differ;  // a point on a square's edge to within float rounding
      continue;
    }
    const float w = i < glsl::kShadowMaxCascades ? cascade_blend_weight(cam, b, p, i, x, in[k].x_rel.w, margin_tex) : 0.0f;
    blended += w > 0;
    worst = std::max(worst, double(std::fabs(out[k].result.y - w)));
  }
  std::printf("gow cascade selection: %u points, %u select differently, %u blended, max |GPU - CPU| weight %.3g\n",
              count, differ, blended, worst);
  EXPECT_LE(differ, count / 1000);
  EXPECT_GT(blended, count / 50);
  EXPECT_LT(worst, 1e-3);
}

// A straight shadow edge crossing the seam between two cascades of very different texel sizes
// (camera 1 m above a floor looking down, sun overhead with a 0.1 degree radius, an occluder
// edge 1.5 m up: the true penumbra, 3 mm, is under a texel of either cascade, so each draws
// the edge as wide as its filter, one texel of radius plus the bilinear footprint). Per image
// column across the seam, the edge's width (4 x the sum over rows of min(v, 1 - v): the width of
// a linear ramp). The step: the largest change between adjacent columns, as a share of the
// whole change between the two cascades' widths (medians well inside each). A hard seam puts
// the whole change in one column step (share near 1). A good technique's shadow has no seam: the
// light does not know where a cascade ends. Blending linearly over a band of B columns puts at
// most about 1/B of the change in each column step; the bound allows twice that (the width
// measure is not linear in the blend, and the taps are jittered per pixel).
TEST_F(GowShadowGpu, SeamBlendSpreadsTheStepAcrossTheBand) {
  constexpr uint32_t W = 128, H = 72;
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {40, 40}}, {"facing", "+y"}}},
                                        {"material", "grey"}},
                                       {{"name", "occluder"},
                                        {"primitive", {{"type", "quad"}, {"size", {40, 40}}, {"facing", "-y"}}},
                                        {"material", "grey"},
                                        {"transform", {{"translate", {0, 1.5, -20}}}}}})},
              {"sun", {{"direction", {0, 1, 0}}, {"irradiance", {3, 3, 3}}, {"angular_radius_deg", 0.1}}},
              {"camera",
               {{"position", {0, 1, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fov_y_deg", 60}, {"near", 0.05}}}};
  Scene scene = parse_scene(doc, "gow-seam-test");
  // Two cascades, logarithmic: the first ends at sqrt(0.05 x 7.2) = 0.6 m (its square ~0.71 m
  // from the view's centre), the second reaches 7.2 m (texels 12x larger).
  auto edge_widths = [&](uint32_t filter, double band) {
    const Technique& t = find_technique("gow-ragnarok");
    Settings s;
    s.width = W;
    s.height = H;
    s = apply_preset(t, "medium", s);
    s = apply_options(t, s, {{"shadow_filter", filter}, {"cascades", 2}, {"shadow_distance", 7.2}, {"split_lambda", 1},
                             {"shadow_resolution", 256}, {"taps", 32}, {"march_steps", 16}, {"cascade_blend", band}});
    FloatImage v = render_gow(gpu(), scene, s, {vis_slot(filter)})[vis_slot(filter)];
    std::vector<double> w(W, 0.0);
    for (uint32_t x = 0; x < W; ++x)
      for (uint32_t y = 0; y < H; ++y) w[x] += 4.0 * std::min(v.at(x, y, 0), 1.0f - v.at(x, y, 0));
    return w;
  };
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  for (uint32_t filter : {0u, 1u}) {
    double share[2];
    for (int blend = 0; blend < 2; ++blend) {
      const std::vector<double> w = edge_widths(filter, blend ? 0.1 : 0.0);
      // The right-hand seam (x = +0.71 m, about column 108): cascade 0 left of it, 1 right.
      const double inner = median(std::vector<double>(w.begin() + 70, w.begin() + 88));
      const double outer = median(std::vector<double>(w.begin() + 118, w.end()));
      double step = 0;
      uint32_t at = 0;
      for (uint32_t x = 70; x + 1 < W; ++x)
        if (std::fabs(w[x + 1] - w[x]) > step) step = std::fabs(w[x + 1] - w[x]), at = x;
      share[blend] = step / std::fabs(outer - inner);
      std::printf("%-26s cascade_blend %.1f: edge width %.2f px (cascade 0) -> %.2f px (cascade 1); largest column "
                  "step %.2f px at column %u = %.2f of the change\n",
                  vis_slot(filter), blend ? 0.1 : 0.0, inner, outer, step, at, share[blend]);
      EXPECT_GT(outer, inner + 3.0) << "the two cascades must draw the edge at different widths";
    }
    // Band: 0.1 of the first cascade's width (2 x 0.71 m) at 1.6 cm per pixel: about 9 columns.
    const double band_cols = 0.1 * 2 * 0.71 / (2 * 1.0 * std::tan(30.0 * kPi / 180.0) * (double(W) / H) / W);
    EXPECT_GT(share[0], 0.5) << vis_slot(filter) << ": the control (no blend) must show the seam";
    EXPECT_LT(share[1], 2.0 / band_cols) << vis_slot(filter) << ": band " << band_cols << " columns";
  }
}

}  // namespace
}  // namespace gib
