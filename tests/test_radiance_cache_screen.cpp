// GPU tests of the radiance-cache technique's screen-space half: final_gather, gi_denoise,
// gi_upscale, composite (lavapipe, small sizes). The world-sampling passes are replaced by a
// test-only pass that provides zeroed rc_cells / probe atlases (so the world cache never
// answers and the volumes return 0): these tests isolate the screen half.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/techniques/radiance_cache/exposure/exposure.h"
#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "renderer/techniques/radiance_cache/final_gather/final_gather.h"
#include "renderer/techniques/radiance_cache/final_gather/final_gather_shared.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise.h"
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite.h"
#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve.h"
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.h"
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update.h"
#include "renderer/techniques/radiance_cache/probe_trace/probe_trace.h"
#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade.h"
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gpu_fixture.h"
#include "tests/rc_screen_synth_gather_shared.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;

// Zeroed world-sampling outputs, with the descs the design gives them.
class StubWorldSampling final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    ResourceDesc cells{Format::buffer, SizeRule::buffer};
    cells.bytes = uint64_t(sizeof(glsl::RcCell)) << rc(s).cache_log2_cells;
    cells.persistent = true;
    ResourceDesc irr{Format::r32_uint, SizeRule::fixed, glsl::kProbeAtlasWidth,
                     glsl::kProbeAtlasRowsPerCascade * rc(s).cascades};
    ResourceDesc vis = irr;
    vis.format = Format::rg16_float;
    irr.persistent = vis.persistent = true;
    return {"stub_world_sampling", PassKind::transfer, {}, {},
            {{"rc_cells", Access::write, cells},
             {"probe_irradiance", Access::write, irr},
             {"probe_visibility", Access::write, vis}}, false};
  }
  void record(RecordContext& ctx) override {
    const float zero[4] = {0, 0, 0, 0};
    ctx.cmd.fill(ctx.buffer("rc_cells"), 0);
    ctx.cmd.clear(ctx.image("probe_irradiance"), zero);
    ctx.cmd.clear(ctx.image("probe_visibility"), zero);
  }
};

// Synthetic gather output (tests/rc_screen_synth_gather.comp) in place of final_gather.
class SynthGather final : public Pass {
 public:
  explicit SynthGather(glsl::SynthPush push) : push_(push) {}
  PassDecl declare(const Scene&, const Settings&) const override {
    ResourceDesc sh{Format::rgba16_float, SizeRule::half};
    return {"synth_gather", PassKind::compute, {}, {},
            {{"gbuffer_position", Access::read},
             {"gather_sh_r", Access::write, sh},
             {"gather_sh_g", Access::write, sh},
             {"gather_sh_b", Access::write, sh},
             {"gather_hit_distance", Access::write, {Format::r32_float, SizeRule::half}},
             {"gather_direct", Access::write, ResourceDesc{Format::rgba16_float, SizeRule::half}.with(non_negative_values())}},
            false};
  }
  void record(RecordContext& ctx) override {
    using namespace glsl;
    record_compute(ctx, {.shader = "rc_screen_synth_gather.comp",
                         .images = {{kSynthBindPosition, "gbuffer_position"},
                                    {kSynthBindShR, "gather_sh_r"},
                                    {kSynthBindShG, "gather_sh_g"},
                                    {kSynthBindShB, "gather_sh_b"},
                                    {kSynthBindHit, "gather_hit_distance"},
                                    {kSynthBindDirect, "gather_direct"}},
                         .groups_x = div_up(ctx.width("gather_hit_distance"), kSynthGroup),
                         .groups_y = div_up(ctx.height("gather_hit_distance"), kSynthGroup),
                         .push = &push_,
                         .push_bytes = sizeof(push_),
                         .scene = false});
  }

 private:
  glsl::SynthPush push_;
};

std::vector<std::unique_ptr<Pass>> screen_passes() {
  std::vector<std::unique_ptr<Pass>> p;
  p.push_back(make_visibility_pass());
  p.push_back(make_gbuffer_pass());
  p.push_back(make_direct_lighting_pass());
  p.push_back(std::make_unique<StubWorldSampling>());
  p.push_back(make_exposure_pass());
  p.push_back(make_final_gather_pass());
  p.push_back(make_gi_denoise_pass());
  p.push_back(make_gi_upscale_pass());
  p.push_back(make_gi_composite_pass());
  p.push_back(make_gi_resolve_pass());
  return p;
}

Settings small_settings(uint32_t w = 64, uint32_t h = 36) {
  Settings s = defaults_of("radiance-cache");
  s.width = w;
  s.height = h;
  // The sky's first bounce comes from the gather (its misses), not from direct_lighting.
  sky_rays(s) = 0;
  rc(s).cache_log2_cells = 10;
  rc(s).cascades = 1;
  rc(s).history_max_frames = 8;
  return s;
}

// Floor, a red box and a sphere under a gradient sky with a sun.
Scene box_scene(const char* extra_box = "") {
  std::string json = std::string(R"({
    "materials": {"white": {"albedo": [0.7, 0.7, 0.7]}, "red": {"albedo": [0.8, 0.1, 0.1]}},
    "objects": [
      {"primitive": {"type": "quad", "size": [20, 20], "facing": "+y"}, "material": "white"},
      {"primitive": {"type": "box", "size": [1, 1, 1]}, "material": "red", )") + extra_box + R"(
       "transform": {"translate": [0, 0.5, 0]}},
      {"primitive": {"type": "sphere", "radius": 0.5}, "material": "white", "transform": {"translate": [1.5, 0.5, 0.5]}}
    ],
    "sun": {"direction": [0.3, 1, 0.2], "irradiance": [2, 2, 2]},
    "sky": {"type": "gradient", "radiance": [0.3, 0.4, 0.8], "horizon": [0.6, 0.6, 0.6], "ground": [0.1, 0.1, 0.1]},
    "frame_time": 1.0,
    "camera": {"position": [0, 3, 5], "target": [0, 0.5, 0], "fov_y_deg": 50}
  })";
  return parse_scene(nlohmann::json::parse(json), "inline");
}

bool finite_nonneg(const FloatImage& img) {
  return std::all_of(img.pixels.begin(), img.pixels.end(), [](float v) { return std::isfinite(v) && v >= 0; });
}

// irradiance / pi at each pixel from both parts of the gather: bounce (gi_irradiance) plus the
// direct part (gi_direct_irradiance: sky and emissive surfaces, the AOV contract's `direct`).
FloatImage total_gi(Executor& ex) {
  FloatImage t = ex.read("gi_irradiance"), d = ex.read("gi_direct_irradiance");
  for (size_t i = 0; i < t.pixels.size(); ++i) t.pixels[i] += d.pixels[i];
  return t;
}

class RadianceCacheScreen : public GpuTest {};

// Constant sky radiance L: every gather ray escapes, so the gather's direct part, the denoise,
// the upscale and the temporal filter must return irradiance / pi = L, and the bounce part 0.
// On the open plane every full-res normal is its gather sample's normal; on the sphere they
// differ (each point of a convex object under a constant sky still sees irradiance pi L).
TEST_F(RadianceCacheScreen, ConstantSkyRoundTripsThroughTheGather) {
  Scene plane = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/sky_plane.json");  // albedo 0.5, sky 2
  Scene sphere = parse_scene(nlohmann::json::parse(R"({
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [{"primitive": {"type": "sphere", "radius": 1}, "material": "grey"}],
    "sky": {"type": "constant", "radiance": [2, 2, 2]},
    "camera": {"position": [0, 0.5, 3], "target": [0, 0, 0], "fov_y_deg": 50}
  })"), "inline");
  for (const Scene* scene : {&plane, &sphere}) {
    const char* name = scene == &plane ? "plane" : "sphere";
    Settings s = small_settings();
    Executor ex(gpu(), *scene, s, screen_passes(), {"final_color", "indirect_diffuse", "direct_radiance", "gi_irradiance", "gi_direct_irradiance"});
    for (int f = 0; f < 12; ++f) ex.run_frame();
    FloatImage gi = ex.read("gi_direct_irradiance"), bounce = ex.read("gi_irradiance");
    FloatImage ind = ex.read("indirect_diffuse"), dir = ex.read("direct_radiance"), pos = ex.read("gbuffer_position");
    double sum = 0, worst = 0;
    size_t count = 0;
    for (uint32_t y = 0; y < gi.height; ++y)
      for (uint32_t x = 0; x < gi.width; ++x) {
        if (pos.at(x, y, 3) == 0) continue;
        for (uint32_t c = 0; c < 3; ++c) {
          sum += gi.at(x, y, c);
          ++count;
          worst = std::max(worst, std::abs(gi.at(x, y, c) / 2.0 - 1.0));
          EXPECT_EQ(bounce.at(x, y, c), 0.0f);
          EXPECT_EQ(ind.at(x, y, c), 0.0f);
          EXPECT_NEAR(dir.at(x, y, c), 0.5f * gi.at(x, y, c), 1e-3f);
        }
      }
    double mean = sum / double(count);
    std::vector<uint8_t> raw = ex.read_buffer("gather_stats");
    uint32_t stats[4];
    std::memcpy(stats, raw.data(), sizeof(stats));
    std::printf("sky round trip (%s): mean gi_direct_irradiance %.4f (sky 2), worst pixel %.2f%%; rays: screen %u world %u "
                "volume %u sky %u\n", name, mean, 100 * worst, stats[0], stats[1], stats[2], stats[3]);
    RecordProperty(std::string("sky_mean_relative_error_") + name, std::to_string(mean / 2.0 - 1.0));
    ASSERT_GT(count, 300u) << name;
    EXPECT_NEAR(mean, 2.0, 0.03 * 2.0) << name;
    // Exact up to RGBA16F rounding of gather_direct and RGB9E5 of the history.
    EXPECT_LT(worst, 0.005) << name;
    EXPECT_EQ(stats[0] + stats[1] + stats[2], 0u) << name;
    EXPECT_GT(stats[glsl::kGatherStatSky], 0u) << name;
    if (scene == &plane) {
      EXPECT_EQ(stats[glsl::kGatherStatSky], 32u * 18u);
    }
  }
}

// Pre-exposure (exposure pass): a sphere on a grey ground under a sky of 20000, against the
// same scene under a sky of 2 (light is linear: every irradiance scales by 10000). The gather
// SH (RGBA16F, max 65504) hold the bounce light off the ground (~0.5 x 20000 radiance) and a
// grazing sample's L1 reaches ~157 x 0.49 x L = 7.7e5: without pre-exposure those clamp; with
// it the SH hold L x P, P ~ 1 / the frame's log-average luminance, and the result (divided by
// P) must be 10000 x the radiance-2 one.
TEST_F(RadianceCacheScreen, PreExposureKeepsABrightSkyInRange) {
  auto scene_with_sky = [](double sky) {
    nlohmann::json doc = nlohmann::json::parse(R"({
      "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"primitive": {"type": "quad", "size": [40, 40], "facing": "+y"}, "material": "grey"},
                  {"primitive": {"type": "sphere", "radius": 1}, "material": "grey", "transform": {"translate": [0, 1, 0]}}],
      "camera": {"position": [0, 1.5, 4], "target": [0, 0.8, 0], "fov_y_deg": 50}
    })");
    doc["sky"] = {{"type", "constant"}, {"radiance", {sky, sky, sky}}};
    return parse_scene(doc, "inline");
  };
  auto run = [&](double sky, bool pre_exposure, double& sh_max, size_t& saturated, float& p0) {
    Settings s = small_settings();
    rc(s).pre_exposure = pre_exposure;
    const Scene scene = scene_with_sky(sky);  // the executor keeps a reference
    Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_irradiance", "gi_direct_irradiance"});
    for (int f = 0; f < 12; ++f) ex.run_frame();
    FloatImage gi = total_gi(ex), pos = ex.read("gbuffer_position"), sh = ex.read("gather_sh_r");
    std::vector<uint8_t> raw = ex.read_buffer("exposure");
    float p[glsl::kExposureWords];
    std::memcpy(p, raw.data(), sizeof(p));
    p0 = p[0];
    double sum = 0;
    size_t count = 0;
    for (uint32_t y = 0; y < gi.height; ++y)
      for (uint32_t x = 0; x < gi.width; ++x)
        if (pos.at(x, y, 3) != 0) {
          sum += gi.at(x, y, 0);
          ++count;
        }
    sh_max = 0;
    saturated = 0;
    for (float v : sh.pixels) {
      sh_max = std::max(sh_max, double(std::abs(v)));
      saturated += std::abs(v) >= 65504.0f;
    }
    EXPECT_GT(count, 300u);
    return sum / double(count);
  };
  double sh_max;
  size_t saturated;
  float p0;
  const double base = run(2.0, true, sh_max, saturated, p0);
  for (bool pre_exposure : {false, true}) {
    const double mean = run(20000.0, pre_exposure, sh_max, saturated, p0);
    std::printf("sky 20000, pre_exposure %d: P %.4g, mean irradiance / pi %.1f (%.2f%% off 10000 x the sky-2 "
                "run's %.4f), gather_sh_r max |c| %.1f, %zu coefficients at 65504\n", int(pre_exposure), p0, mean,
                100 * (mean / (10000 * base) - 1), base, sh_max, saturated);
    RecordProperty(std::string("bright_sky_relative_error_pe") + (pre_exposure ? "1" : "0"),
                   std::to_string(mean / (10000 * base) - 1));
    if (pre_exposure) {
      EXPECT_GT(p0, 1.0f / 80000.0f);  // of the order of 1 / the frame's luminance
      EXPECT_LT(p0, 1.0f / 2500.0f);
      EXPECT_EQ(saturated, 0u);
      EXPECT_LT(sh_max, 65504.0 / 16);
      EXPECT_NEAR(mean, 10000 * base, 0.03 * 10000 * base);
    } else {
      EXPECT_EQ(p0, 1.0f);
      EXPECT_GT(saturated, 0u);
    }
  }
}

// The sky's first bounce is counted once: by the gather when direct_lighting traces no sky
// rays, else by direct_lighting alone. A plane of albedo a under sky L is a L both ways.
TEST_F(RadianceCacheScreen, SkyIsCountedOnceWhicheverPassTracesIt) {
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/sky_plane.json");  // albedo 0.5, sky 2
  for (uint32_t rays : {0u, 4u}) {
    Settings s = small_settings();
    sky_rays(s) = rays;
    Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_irradiance", "gi_direct_irradiance"});
    for (int f = 0; f < 3; ++f) ex.run_frame();
    FloatImage out = ex.read("final_color"), gi = ex.read("gi_irradiance");
    double worst = 0, gi_max = 0;
    for (uint32_t y = 0; y < out.height; ++y)
      for (uint32_t x = 0; x < out.width; ++x)
        for (uint32_t c = 0; c < 3; ++c) {
          worst = std::max(worst, std::abs(double(out.at(x, y, c)) - 1.0));
          gi_max = std::max(gi_max, double(gi.at(x, y, c)));
        }
    std::printf("sky_rays %u: max |final_color - a L| = %.2g, max gi_irradiance %.3g\n", rays, worst, gi_max);
    EXPECT_LT(worst, 5e-3) << "sky_rays " << rays;
    if (rays > 0) {
      EXPECT_EQ(gi_max, 0.0);
    }
  }
}

// Static camera: n climbs 1, 2, ... to n_max and stays; after that a frame moves the average by
// at most 1 / (n_max + 1) of the way to the new sample (with the exact RGBA32F history,
// G_t >= G_{t-1} n / (n + 1) since the sample is >= 0).
TEST_F(RadianceCacheScreen, TemporalFilterAccumulatesToNMax) {
  Scene scene = box_scene();
  Settings s = small_settings();
  rc(s).history_format = 3;
  const uint32_t n_max = rc(s).history_max_frames;
  Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_irradiance", "gi_direct_irradiance"});
  FloatImage prev;
  double first_change = 0, last_change = 0;
  for (uint32_t f = 0; f < n_max + 4; ++f) {
    ex.run_frame();
    FloatImage n = ex.read("gi_history_frames"), pos = ex.read("gbuffer_position"), gi = total_gi(ex);
    const float expect = float(std::min(f + 1, n_max));
    size_t surface = 0, match = 0, below = 0;
    double change = 0, level = 0;
    for (uint32_t y = 0; y < n.height; ++y)
      for (uint32_t x = 0; x < n.width; ++x) {
        if (pos.at(x, y, 3) == 0) continue;
        ++surface;
        match += n.at(x, y, 0) == expect;
        if (f == 0) continue;
        for (uint32_t c = 0; c < 3; ++c) {
          change += std::abs(gi.at(x, y, c) - prev.at(x, y, c));
          level += gi.at(x, y, c);
          if (f >= n_max && gi.at(x, y, c) < prev.at(x, y, c) * n_max / (n_max + 1.0f) * (1 - 1e-5f)) ++below;
        }
      }
    ASSERT_GT(surface, 0u);
    EXPECT_GE(double(match), 0.98 * surface) << "frame " << f << ": n should be " << expect;
    EXPECT_EQ(below, 0u) << "frame " << f;
    if (f == 1) first_change = change / level;
    if (f > 0) last_change = change / level;
    prev = gi;
  }
  std::printf("temporal: mean relative frame-to-frame change %.4f (frame 1) -> %.4f (frame %u)\n", first_change,
              last_change, n_max + 3);
  EXPECT_LT(last_change, 0.5 * first_change);
  EXPECT_LT(last_change, 2.0 / (n_max + 1));
}

// A box jumps 1 m sideways between two frames (static camera): pixels whose surface changed
// restart at n = 1, pixels that kept their surface keep n_max. Without disocclusion tests no
// surface pixel restarts.
TEST_F(RadianceCacheScreen, DisocclusionResetsOnlyWhereTheSurfaceChanged) {
  Scene scene = box_scene(R"("animation": [{"time": 0, "translate": [0, 0.5, 0]}, {"time": 10, "translate": [0, 0.5, 0]},
                                           {"time": 11, "translate": [1, 0.5, 0]}],)");
  for (bool disocclusion : {true, false}) {
    Settings s = small_settings();
    rc(s).disocclusion = disocclusion;
    const float n_max = float(rc(s).history_max_frames);
    Executor ex(gpu(), scene, s, screen_passes(), {"final_color"});
    for (int f = 0; f <= 10; ++f) ex.run_frame();
    FloatImage p0 = ex.read("gbuffer_position");
    ex.run_frame();
    FloatImage p1 = ex.read("gbuffer_position"), n = ex.read("gi_history_frames");
    size_t same = 0, same_ok = 0, changed = 0, changed_ok = 0;
    for (uint32_t y = 0; y < n.height; ++y)
      for (uint32_t x = 0; x < n.width; ++x) {
        float d1 = p1.at(x, y, 3);
        if (d1 == 0) continue;
        float moved = 0;
        for (uint32_t c = 0; c < 3; ++c) moved = std::max(moved, std::abs(p1.at(x, y, c) - p0.at(x, y, c)));
        if (p0.at(x, y, 3) != 0 && moved < 0.01f * d1) {
          ++same;
          same_ok += n.at(x, y, 0) == n_max;
        } else if (p0.at(x, y, 3) != 0 && moved > 0.2f * d1) {
          ++changed;
          changed_ok += n.at(x, y, 0) == (disocclusion ? 1.0f : n_max);
        }
      }
    std::printf("disocclusion %s: %zu/%zu unchanged pixels kept n_max, %zu/%zu changed pixels %s\n",
                disocclusion ? "on" : "off", same_ok, same, changed_ok, changed,
                disocclusion ? "restarted" : "kept n_max");
    ASSERT_GT(changed, 20u);
    ASSERT_GT(same, 500u);
    EXPECT_GE(double(same_ok), 0.98 * same);
    EXPECT_GE(double(changed_ok), 0.95 * changed);
  }
}

// A small camera move: reprojected history survives on most of the image, only newly revealed
// pixels restart.
TEST_F(RadianceCacheScreen, CameraMoveKeepsReprojectedHistory) {
  Scene scene = box_scene();
  scene.camera.animation = {{0, {0, 3, 5}, {0, 0.5f, 0}, 50}, {6, {0, 3, 5}, {0, 0.5f, 0}, 50},
                            {7, {0.3f, 3, 5}, {0.3f, 0.5f, 0}, 50}};
  Settings s = small_settings();
  Executor ex(gpu(), scene, s, screen_passes(), {"final_color"});
  for (int f = 0; f <= 7; ++f) ex.run_frame();
  FloatImage n = ex.read("gi_history_frames"), pos = ex.read("gbuffer_position");
  size_t surface = 0, kept = 0, restarted = 0;
  for (uint32_t y = 0; y < n.height; ++y)
    for (uint32_t x = 0; x < n.width; ++x) {
      if (pos.at(x, y, 3) == 0) continue;
      ++surface;
      kept += n.at(x, y, 0) >= 7.0f;  // n was 7 before the move: 8 when reprojected
      restarted += n.at(x, y, 0) == 1.0f;
    }
  std::printf("camera move: %zu/%zu surface pixels kept history, %zu restarted\n", kept, surface, restarted);
  EXPECT_GE(double(kept), 0.85 * surface);
  EXPECT_GT(restarted, 0u);
}

// Two planes at different depths (floor and the top of a tall block, seen from above): the
// bilateral denoise smooths the noise on each and never mixes them across the edge.
TEST_F(RadianceCacheScreen, DenoiseDoesNotBlurAcrossADepthEdge) {
  Scene scene = parse_scene(nlohmann::json::parse(R"({
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [
      {"primitive": {"type": "quad", "size": [60, 60], "facing": "+y"}, "material": "grey"},
      {"primitive": {"type": "box", "size": [20, 3, 40]}, "material": "grey", "transform": {"translate": [10, 1.5, 0]}}
    ],
    "sky": {"type": "constant", "radiance": [1, 1, 1]},
    "camera": {"position": [0, 10, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov_y_deg": 60}
  })"), "inline");
  Settings s = small_settings();
  rc(s).denoise_radius = 3;
  const float low = 1, high = 4, noise = 0.5f;
  std::vector<std::unique_ptr<Pass>> passes;
  passes.push_back(make_visibility_pass());
  passes.push_back(make_gbuffer_pass());
  passes.push_back(std::make_unique<SynthGather>(glsl::SynthPush{2, 1.5f, low, high, noise, 0, 0, 0}));
  passes.push_back(make_gi_denoise_pass());
  Executor ex(gpu(), scene, s, std::move(passes), {"gi_sh_r", "gi_direct"});
  ex.run_frame();
  // The bounce SH and the direct part (geometry weights only) are both checked.
  for (const char* name : {"gi_sh_r", "gi_direct"}) {
  SCOPED_TRACE(name);
  FloatImage raw = ex.read("gather_sh_r"), out = ex.read(name), pos = ex.read("gbuffer_position");
  double worst_edge = 0, var_in = 0, var_out = 0;
  size_t edge = 0, interior = 0;
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      uint32_t px = std::min(2 * x + 1, pos.width - 1), py = std::min(2 * y + 1, pos.height - 1);
      if (pos.at(px, py, 3) == 0) continue;
      float expect = pos.at(px, py, 1) > 1.5f ? high : low;
      // Distance (gather pixels) to the nearest pixel of the other plane along the row.
      int nearest_other = 1000;
      for (uint32_t x2 = 0; x2 < out.width; ++x2) {
        uint32_t qx = std::min(2 * x2 + 1, pos.width - 1);
        if ((pos.at(qx, py, 1) > 1.5f) != (expect == high))
          nearest_other = std::min(nearest_other, std::abs(int(x2) - int(x)));
      }
      double err = std::abs(out.at(x, y, 0) - expect);
      if (nearest_other <= int(rc(s).denoise_radius)) {
        ++edge;
        worst_edge = std::max(worst_edge, err);
      } else if (nearest_other > 2 * int(rc(s).denoise_radius) && y > 3 && y + 3 < out.height) {
        ++interior;
        var_in += std::pow(raw.at(x, y, 0) - expect, 2);
        var_out += std::pow(out.at(x, y, 0) - expect, 2);
      }
    }
  double rms_in = std::sqrt(var_in / interior), rms_out = std::sqrt(var_out / interior);
  std::printf("denoise edge (%s): %zu edge pixels, worst |value - own plane| %.3f (planes %.0f / %.0f, noise +-%.1f); "
              "interior rms noise %.3f -> %.3f\n", name, edge, worst_edge, low, high, noise, rms_in, rms_out);
  ASSERT_GT(edge, 10u);
  ASSERT_GT(interior, 50u);
  EXPECT_LT(worst_edge, noise);    // a mix across the edge would be off by ~(high - low) / 2
  EXPECT_LT(rms_out, 0.5 * rms_in);  // and it does denoise
  }
}

// gi_denoise at its radius bounds: radius 0 is a copy (every gather pixel that is not sky keeps
// its SH and direct part to within the one RGBA16F rounding of (w x value) / w per direction, sky
// pixels are 0), and the option's largest radius (16) runs, stays finite and filters.
TEST_F(RadianceCacheScreen, DenoiseTileKnownAnswersAtRadius0And16) {
  Scene scene = box_scene();
  for (uint32_t radius : {0u, 16u}) {
    SCOPED_TRACE("radius " + std::to_string(radius));
    Settings s = small_settings(72, 40);  // not a multiple of the 8x8 groups at gather resolution
    rc(s).denoise_radius = radius;
    Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"});
    for (int f = 0; f < 3; ++f) ex.run_frame();  // the screen cache answers from frame 1: bounce light in the SH
    FloatImage pos = ex.read("gbuffer_position");
    size_t differing = 0, nonzero = 0, non_finite = 0, values = 0;
    for (const char* in_name : {"gather_sh_r", "gather_sh_g", "gather_sh_b", "gather_direct"}) {
      const std::string out_name = std::string(in_name) == "gather_direct" ? "gi_direct" : "gi_sh_" + std::string(in_name).substr(10);
      FloatImage in = ex.read(in_name), out = ex.read(out_name.c_str());
      for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
          uint32_t px = std::min(2 * x + 1, pos.width - 1), py = std::min(2 * y + 1, pos.height - 1);
          const bool sky = pos.at(px, py, 3) == 0;
          for (uint32_t c = 0; c < 4; ++c) {
            float o = out.at(x, y, c), expect = sky ? 0.0f : in.at(x, y, c);
            ++values;
            nonzero += o != 0;
            non_finite += !std::isfinite(o);
            differing += !(std::abs(o - expect) <= std::abs(expect) * 0x1p-9f);  // 2 half ulps: 2 directions
          }
        }
    }
    std::printf("denoise radius %u: %zu of %zu values differ from the gather by more than 2 half ulps (%zu non-zero, "
                "%zu non-finite)\n", radius,
                differing, values, nonzero, non_finite);
    EXPECT_GT(nonzero, values / 8);
    EXPECT_EQ(non_finite, 0u);
    if (radius == 0) {
      EXPECT_EQ(differing, 0u);
    } else {
      EXPECT_GT(differing, values / 8);  // radius 16 does filter
    }
  }
}

// Values of a and b (float bit patterns) that differ: a NaN equals any NaN (its payload may
// differ between two paths that both propagate it).
size_t bits_differ(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
  size_t n = 0;
  auto nan = [](uint32_t u) { return (u & 0x7fffffffu) > 0x7f800000u; };
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] && !(nan(a[i]) && nan(b[i]));
  return n;
}

// A NaN G-buffer normal written at frame 1 on the representative pixel of a gather pixel near
// the centre (as tests/test_nan_guards.cpp), with the NaN guards on or off.
void inject_nan_normal(Settings& s, bool guards) {
  const uint32_t div = gather_divisor(rc(s));
  s.nan_guards = guards;
  s.debug.inject_nan = 1;
  s.debug.inject_frame = 1;
  s.debug.inject_x = s.width / 2 / div * div + div / 2;
  s.debug.inject_y = s.height / 2 / div * div + div / 2;
}

// The checks of a kernel-agreement test: the tiled kernel's values equal the per-tap kernel's bit
// for bit (a NaN equals a NaN), more than min_nonzero of them are not 0 (else the comparison sees
// nothing), and NaNs reach the output exactly when `expect_nan` (a NaN injected, guards off).
void expect_kernels_agree(const std::vector<uint32_t>& tiled, const std::vector<uint32_t>& per_tap, double min_nonzero,
                          bool expect_nan) {
  ASSERT_EQ(tiled.size(), per_tap.size());
  size_t nonzero = 0, nan = 0;
  for (uint32_t u : per_tap) {
    nonzero += (u & 0x7fffffffu) != 0;
    nan += (u & 0x7fffffffu) > 0x7f800000u;
  }
  EXPECT_EQ(bits_differ(tiled, per_tap), 0u) << "of " << tiled.size() << " values";
  EXPECT_GT(double(nonzero), min_nonzero * double(tiled.size())) << "the outputs are mostly zero: the comparison sees nothing";
  if (expect_nan) {
    EXPECT_GT(nan, 0u) << "without guards the injected NaN must reach the output";
  } else {
    EXPECT_EQ(nan, 0u);
  }
}

// gi_denoise's three kernels (denoise_kernel 0: both directions in one dispatch over a
// group-shared tile, up to radius 4, else as 2; 1: two dispatches, each tap reads the images; 2:
// two dispatches, taps preloaded to a group-shared tile along the axis) give the same SH and
// direct part bit for bit, frame after frame, at radii up to the tiles' limits, with the
// hit-distance weight off and on, on a size whose gather resolution is not a multiple of the 8x8
// groups (partial tiles at the right and bottom edges). A tile indexed one texel off, a tap
// outside the image not skipped, or a horizontal result kept at another precision than the
// RGBA16F image holds, fails it.
TEST_F(RadianceCacheScreen, DenoiseKernelsAgreeBitForBit) {
  Scene scene = box_scene();
  // mode 0: no injection; 1, 2: a NaN normal with the guards on, off.
  for (uint32_t radius : {1u, glsl::kDenoiseFusedMaxRadius, glsl::kDenoiseTileMaxRadius})
    for (uint32_t hit_weight : {0u, 1u})
      for (int mode = 0; mode < 3; ++mode) {
        SCOPED_TRACE("radius " + std::to_string(radius) + ", hit weight " + std::to_string(hit_weight) +
                     (mode == 0 ? "" : mode == 1 ? ", NaN normal, guards on" : ", NaN normal, guards off"));
        auto run = [&](uint32_t kernel) {
          Settings s = small_settings(72, 40);
          rc(s).denoise_radius = radius;
          rc(s).denoise_hit_weight = hit_weight;
          rc(s).denoise_kernel = kernel;
          if (mode) inject_nan_normal(s, mode == 1);
          Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"});
          std::vector<uint32_t> bits;
          for (int f = 0; f < 3; ++f) {  // the screen cache answers from frame 1: bounce light in the SH
            ex.run_frame();
            for (const char* name : {"gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"})
              for (float v : ex.read(name).pixels) bits.push_back(std::bit_cast<uint32_t>(v));
          }
          return bits;
        };
        const std::vector<uint32_t> per_tap = run(1);
        expect_kernels_agree(run(0), per_tap, 1.0 / 8, mode == 2);
        expect_kernels_agree(run(2), per_tap, 1.0 / 8, mode == 2);
      }
}

// The tiled denoise kernels test each tile texel's values for the NaN guard once, the per-tap
// kernel at every tap: on a synthetic gather with a NaN in some pixels' SH, all skip the same taps
// (the output is finite and equal bit for bit), and without guards all spread the NaN.
TEST_F(RadianceCacheScreen, DenoiseKernelsSkipTheSameNanTaps) {
  Scene scene = box_scene();
  for (bool guards : {true, false}) {
    SCOPED_TRACE(guards ? "guards on" : "guards off");
    auto run = [&](uint32_t kernel) {
      Settings s = small_settings(72, 40);
      s.nan_guards = guards;
      rc(s).denoise_kernel = kernel;
      std::vector<std::unique_ptr<Pass>> passes;
      passes.push_back(make_visibility_pass());
      passes.push_back(make_gbuffer_pass());
      passes.push_back(std::make_unique<SynthGather>(glsl::SynthPush{2, 1.5f, 1, 4, 0.5f, 5, 0, 0}));
      passes.push_back(make_gi_denoise_pass());
      Executor ex(gpu(), scene, s, std::move(passes), {"gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"});
      ex.run_frame();
      std::vector<uint32_t> bits;
      for (const char* name : {"gi_sh_r", "gi_sh_g", "gi_sh_b", "gi_direct"})
        for (float v : ex.read(name).pixels) bits.push_back(std::bit_cast<uint32_t>(v));
      return bits;
    };
    const std::vector<uint32_t> per_tap = run(1);
    expect_kernels_agree(run(0), per_tap, 1.0 / 8, !guards);
    expect_kernels_agree(run(2), per_tap, 1.0 / 8, !guards);
  }
}

// gi_upscale's two kernels (upscale_kernel 0: the group's gather samples preloaded to a
// group-shared tile; 1: each tap reads the images) give the same history, frame counter and
// outputs bit for bit, frame after frame, at every gather divisor (the tile's extent differs:
// 11, 8 and 6 gather pixels), on a size that is not a multiple of the 8x8 groups, with the
// camera moving between frames (so the history is reprojected, not copied).
TEST_F(RadianceCacheScreen, UpscaleKernelsAgreeBitForBit) {
  Scene scene = box_scene();
  scene.camera.animation = {{0, {0, 3, 5}, {0, 0.5f, 0}, 50}, {3, {0.3f, 3.1f, 5}, {0.3f, 0.5f, 0}, 50}};
  // mode 0: no injection; 1, 2: a NaN normal with the guards on, off (history RGBA16F, which can
  // hold the NaN).
  for (uint32_t divisor : {1u, 2u, 4u})
    for (int mode = 0; mode < 3; ++mode) {
      SCOPED_TRACE("divisor " + std::to_string(divisor) +
                   (mode == 0 ? "" : mode == 1 ? ", NaN normal, guards on" : ", NaN normal, guards off"));
      auto run = [&](uint32_t kernel) {
        Settings s = small_settings(76, 44);
        rc(s).gather_divisor = divisor;
        rc(s).upscale_kernel = kernel;
        if (mode) {
          inject_nan_normal(s, mode == 1);
          rc(s).history_format = 1;
        }
        Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_irradiance", "gi_direct_irradiance"});
        std::vector<uint32_t> bits;
        for (int f = 0; f < 4; ++f) {  // the screen cache answers from frame 1: bounce light in the SH
          ex.run_frame();
          for (const char* name : {"gi_irradiance", "gi_direct_irradiance", "gi_history_frames"})
            for (float v : ex.read(name).pixels) bits.push_back(std::bit_cast<uint32_t>(v));
        }
        return bits;
      };
      expect_kernels_agree(run(0), run(1), 1.0 / 4, mode == 2);
    }
}

// Every history format runs; RGB9E5 and RGBA16F stay within their precision of RGBA32F (the
// recursive filter's rounding error is bounded by (n_max + 1) / 2 ulp), R11G11B10F is reported.
TEST_F(RadianceCacheScreen, HistoryFormatsAgreeWithinTheirPrecision) {
  Scene scene = box_scene();
  std::vector<FloatImage> results;
  for (uint32_t format = 0; format < 4; ++format) {
    Settings s = small_settings();
    rc(s).history_format = format;
    Executor ex(gpu(), scene, s, screen_passes(), {"final_color", "gi_irradiance", "gi_direct_irradiance"});
    EXPECT_EQ(ex.plan().find("gi_history")->desc.format, gi_history_format(format));
    for (int f = 0; f < 12; ++f) ex.run_frame();
    results.push_back(total_gi(ex));
    EXPECT_TRUE(finite_nonneg(results.back())) << "format " << format;
    EXPECT_TRUE(finite_nonneg(ex.read("final_color"))) << "format " << format;
  }
  const double n_max = rc(small_settings()).history_max_frames;
  // Relative precision of one rounding, relative to the pixel's largest channel: RGB9E5 shares
  // the exponent (9-bit mantissa, round to nearest: 2^-9 of the max at worst); half rounds by
  // the device's rule (lavapipe truncates: 2^-10); R11G11B10F truncates (blue: 5 bits, 2^-5).
  const double ulp[4] = {1.0 / 256, 1.0 / 1024, 1.0 / 32, 0};
  const char* names[4] = {"rgb9e5", "rgba16f", "r11g11b10f", "rgba32f"};
  const FloatImage& ref = results[3];
  for (int format = 0; format < 3; ++format) {
    double worst = 0, mean_err = 0, mean_ref = 0;
    for (uint32_t y = 0; y < ref.height; ++y)
      for (uint32_t x = 0; x < ref.width; ++x) {
        double mx = std::max({ref.at(x, y, 0), ref.at(x, y, 1), ref.at(x, y, 2)});
        for (uint32_t c = 0; c < 3; ++c) {
          double d = std::abs(results[format].at(x, y, c) - ref.at(x, y, c));
          mean_err += d;
          mean_ref += ref.at(x, y, c);
          if (mx > 1e-3) worst = std::max(worst, d / mx);
        }
      }
    std::printf("history %s vs rgba32f: worst %.3f%% of the pixel's max channel, mean %.3f%%\n", names[format],
                100 * worst, 100 * mean_err / mean_ref);
    RecordProperty(std::string("history_") + names[format] + "_worst", std::to_string(worst));
    if (format < 2) {
      EXPECT_LE(worst, (n_max + 1) * ulp[format]) << names[format];
    }
    EXPECT_LE(worst, (n_max + 1) * ulp[2]) << names[format];
  }
}

// With the real world-sampling passes instead of the stub: every cache answers some rays, and
// the image stays finite.
TEST_F(RadianceCacheScreen, FullChainWithWorldSamplingPasses) {
  Scene scene = box_scene();
  Settings s = small_settings();
  std::vector<std::unique_ptr<Pass>> passes;
  passes.push_back(make_visibility_pass());
  passes.push_back(make_gbuffer_pass());
  passes.push_back(make_direct_lighting_pass());
  passes.push_back(make_probe_trace_pass());
  passes.push_back(make_radiance_cache_update_pass());
  passes.push_back(make_radiance_cache_shade_pass());
  passes.push_back(make_irradiance_volume_update_pass());
  passes.push_back(make_exposure_pass());
  passes.push_back(make_final_gather_pass());
  passes.push_back(make_gi_denoise_pass());
  passes.push_back(make_gi_upscale_pass());
  passes.push_back(make_gi_composite_pass());
  Executor ex(gpu(), scene, s, std::move(passes), {"final_color"});
  for (auto& p : ex.plan().passes) EXPECT_TRUE(p.runs) << p.name << ": " << p.reason;
  uint32_t total[4] = {};
  for (int f = 0; f < 8; ++f) {
    ex.run_frame();
    std::vector<uint8_t> raw = ex.read_buffer("gather_stats");
    uint32_t stats[4];
    std::memcpy(stats, raw.data(), sizeof(stats));
    for (int i = 0; i < 4; ++i) total[i] += stats[i];
  }
  FloatImage out = ex.read("final_color"), ind = ex.read("indirect_diffuse");
  double mean_indirect = 0;
  for (float v : ind.pixels) mean_indirect += v;
  mean_indirect /= double(ind.pixels.size());
  std::printf("full chain, 8 frames: rays served by screen %u, world %u, volume %u, sky %u; mean indirect %.4f\n",
              total[0], total[1], total[2], total[3], mean_indirect);
  EXPECT_TRUE(finite_nonneg(out));
  EXPECT_TRUE(finite_nonneg(ind));
  EXPECT_GT(total[glsl::kGatherStatScreen], 0u);
  EXPECT_GT(total[glsl::kGatherStatWorld] + total[glsl::kGatherStatVolume], 0u);
  EXPECT_GT(total[glsl::kGatherStatSky], 0u);
  EXPECT_GT(mean_indirect, 0.0);
}

TEST_F(RadianceCacheScreen, PassTimesAt128x72) {
  Scene scene = box_scene();
  Settings s = small_settings(128, 72);
  rc(s).history_max_frames = 16;
  Executor ex(gpu(), scene, s, screen_passes(), {"final_color"});
  ex.run_frame();  // pipelines compiled
  std::map<std::string, double> ms;
  const int frames = 4;
  for (int f = 0; f < frames; ++f)
    for (auto& p : ex.run_frame().passes) ms[p.name] += p.ms / frames;
  for (const char* name : {"final_gather", "gi_denoise", "gi_upscale", "gi_composite"}) {
    std::printf("%s: %.3f ms (%s, 128x72)\n", name, ms[name], gpu().info().name.c_str());
    RecordProperty(std::string(name) + "_ms", std::to_string(ms[name]));
    EXPECT_GT(ms[name], 0.0);
  }
  EXPECT_TRUE(finite_nonneg(ex.read("final_color")));
}

}  // namespace
}  // namespace gib
