// Integration tests of the `direct` and `reference` techniques on lavapipe at small sizes.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;

std::string scene_path(const char* name) { return std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + name; }

struct Rendered {
  FloatImage out;
  std::map<std::string, FloatImage> extra;
  Plan plan;
};

Rendered render(Gpu& gpu, const Scene& scene, const std::string& technique, uint32_t w, uint32_t h, uint32_t frames,
                uint32_t spp_per_frame = 1, std::vector<std::string> extra = {}, const std::string& preset = "medium") {
  const Technique& t = find_technique(technique);
  Settings s;
  s.width = w;
  s.height = h;
  s = apply_preset(t, preset, s);
  if (s.has_params<ReferenceSettings>()) ref(s).spp_per_frame = spp_per_frame;
  std::vector<std::string> outputs{t.output};
  outputs.insert(outputs.end(), extra.begin(), extra.end());
  Executor ex(gpu, scene, s, make_passes(t), outputs);
  for (uint32_t f = 0; f < frames; ++f) ex.run_frame();
  Rendered r{ex.read(t.output), {}, ex.plan()};
  for (auto& e : extra) r.extra[e] = ex.read(e);
  return r;
}

double mean_channel(const FloatImage& img, uint32_t c) {
  double s = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) s += img.at(x, y, c);
  return s / (double(img.width) * img.height);
}

class Render : public GpuTest {};

TEST_F(Render, WhiteFurnaceIsOneEverywhereAt256Spp) {
  Scene scene = load_scene(scene_path("furnace.json"));
  // Coverage from the visibility buffer, so the check is known to include object pixels.
  Rendered vis = render(gpu(), scene, "direct", 96, 54, 1, 1, {"vbuffer"});
  size_t covered = 0;
  const FloatImage& vb = vis.extra["vbuffer"];
  for (uint32_t y = 0; y < vb.height; ++y)
    for (uint32_t x = 0; x < vb.width; ++x) covered += vb.at(x, y, 0) != 0;
  ASSERT_GT(covered, vb.width * vb.height / 20) << "furnace objects should cover >5% of the view";

  Rendered ref = render(gpu(), scene, "reference", 96, 54, 16, 16, {}, "ultra");  // 256 spp, 64 bounces
  double worst = 0;
  for (uint32_t y = 0; y < ref.out.height; ++y)
    for (uint32_t x = 0; x < ref.out.width; ++x)
      for (uint32_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(ref.out.at(x, y, c)) - 1.0));
  RecordProperty("furnace_max_abs_error", std::to_string(worst));
  std::printf("white furnace: %zu object pixels, max |radiance - 1| = %.3g\n", covered, worst);
  EXPECT_LT(worst, 0.01);
}

TEST_F(Render, DiffusePlaneUnderUniformSkyIsAlbedoTimesRadiance) {
  Scene scene = load_scene(scene_path("sky_plane.json"));  // albedo 0.5, sky 2
  const double expect = 0.5 * 2.0;
  for (const char* technique : {"reference", "direct"}) {
    Rendered r = render(gpu(), scene, technique, 64, 36, technique == std::string("reference") ? 4 : 1, 16);
    double worst = 0;
    for (uint32_t y = 0; y < r.out.height; ++y)
      for (uint32_t x = 0; x < r.out.width; ++x)
        for (uint32_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(r.out.at(x, y, c)) - expect));
    std::printf("sky plane (%s): max |radiance - a*L| = %.3g\n", technique, worst);
    EXPECT_LT(worst, 1e-3) << technique;
  }
}

// A floor, a red box and a white sphere under a point light, viewed from above-front; `sun`
// and `sky` JSON members are spliced in by each test.
Scene lit_objects_scene(const std::string& sun_and_sky) {
  return parse_scene(nlohmann::json::parse(R"({
    "materials": {"white": {"albedo": [0.7, 0.7, 0.7]}, "red": {"albedo": [0.8, 0.1, 0.1]}},
    "objects": [
      {"primitive": {"type": "quad", "size": [20, 20], "facing": "+y"}, "material": "white"},
      {"primitive": {"type": "box", "size": [1, 1, 1]}, "material": "red", "transform": {"translate": [0, 0.5, 0]}},
      {"primitive": {"type": "sphere", "radius": 0.5}, "material": "white", "transform": {"translate": [1.5, 0.5, 0.5]}}
    ],
    "lights": [{"type": "point", "position": [-1, 2, 1], "intensity": [4, 4, 4], "range": 50}],
    "camera": {"position": [0, 3, 5], "target": [0, 0.5, 0], "fov_y_deg": 50},)" + sun_and_sky + "}"),
                     "inline");
}

// The reference's `direct` AOV and the `direct` technique estimate the same quantity with
// different code (path tracer vs G-buffer + shadow rays): their means must agree.
TEST_F(Render, DirectTechniqueMatchesReferenceDirectAov) {
  Scene scene = lit_objects_scene(R"("sun": {"direction": [0.3, 1, 0.2], "irradiance": [2, 2, 2]},
    "sky": {"type": "gradient", "radiance": [0.3, 0.4, 0.8], "horizon": [0.6, 0.6, 0.6], "ground": [0.1, 0.1, 0.1]})");
  Rendered ref = render(gpu(), scene, "reference", 64, 36, 4, 16, {"direct", "indirect_diffuse"});
  Rendered dir = render(gpu(), scene, "direct", 64, 36, 1, 1, {}, "ultra");
  for (uint32_t c = 0; c < 3; ++c) {
    double a = mean_channel(ref.extra["direct"], c), b = mean_channel(dir.out, c);
    std::printf("channel %u: reference direct AOV %.4f, direct technique %.4f\n", c, a, b);
    EXPECT_NEAR(a, b, 0.03 * a) << "channel " << c;
    // radiance = direct + indirect, per pixel
    double r = mean_channel(ref.out, c), i = mean_channel(ref.extra["indirect_diffuse"], c);
    EXPECT_NEAR(r, a + i, 1e-4 * r);
    EXPECT_GT(i, 0.0) << "a floor next to a box must receive some bounce light";
  }
}

TEST_F(Render, SameSeedSameImageOtherSeedOtherImage) {
  Scene scene = load_scene(scene_path("cornell.json"));
  auto run = [&](uint32_t seed) {
    Settings s = defaults_of("reference");
    s.width = 32;
    s.height = 18;
    s.seed = seed;
    ref(s).spp_per_frame = 2;
    Executor ex(gpu(), scene, s, make_passes(find_technique("reference")), {"radiance"});
    ex.run_frame();
    return ex.read("radiance").pixels;
  };
  auto a = run(1), b = run(1), c = run(2);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST_F(Render, EveryPixelFiniteOnFeatureZoo) {
  Scene scene = load_scene(scene_path("features_zoo.json"));
  for (const char* technique : {"direct", "reference"}) {
    Rendered r = render(gpu(), scene, technique, 48, 27, 2, 2);
    size_t bad = 0;
    for (float v : r.out.pixels) bad += !std::isfinite(v) || v < 0;
    EXPECT_EQ(bad, 0u) << technique;
  }
}

size_t non_finite_values(const FloatImage& img) {
  size_t bad = 0;
  for (float v : img.pixels) bad += !std::isfinite(v);
  return bad;
}

// The degenerate-geometry inputs (docs/architecture.md "Determinism and numerical stability"): a mesh whose normals are
// NaN (null in the file) and zero, with zero-area triangles, filling the view. The guards
// (Settings::nan_guards; gib_surface falls back to the face normal) keep every output finite;
// without them the NaN reaches the image, which shows the input does arrive on the GPU as NaN.
TEST_F(Render, NanAndZeroVertexNormalsRenderFinite) {
  Scene scene = parse_scene(nlohmann::json::parse(R"({
    "materials": {"white": {"albedo": [0.7, 0.7, 0.7]}},
    "objects": [
      {"primitive": {"type": "mesh",
                     "positions": [[-3, -2, 0], [3, -2, 0], [3, 2, 0], [-3, 2, 0], [0, 0, 0.5], [0, 0, 0.5], [1, 1, 0]],
                     "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 0], [0, 0, 1], null, [0, 0, 1], [0, 0, 1]],
                     "indices": [[0, 1, 4], [1, 2, 4], [2, 3, 5], [3, 0, 4], [4, 4, 5], [0, 6, 2], [4, 4, 4]]},
       "material": "white"}
    ],
    "lights": [{"type": "point", "position": [1, 1, 2], "intensity": [4, 4, 4]}],
    "sun": {"direction": [0.3, 0.4, 1], "irradiance": [2, 2, 2]},
    "sky": {"type": "constant", "radiance": [0.5, 0.5, 0.5]},
    "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y_deg": 60}
  })"), "nan_normals");
  auto run = [&](const std::string& technique, bool guards, std::vector<std::string> extra = {}) {
    const Technique& t = find_technique(technique);
    Settings s = apply_preset(t, "low", Settings{});
    s.width = 32;
    s.height = 18;
    if (s.has_params<ReferenceSettings>()) ref(s).spp_per_frame = 4;
    s.nan_guards = guards;
    std::vector<std::string> outputs{t.output};
    outputs.insert(outputs.end(), extra.begin(), extra.end());
    Executor ex(gpu(), scene, s, make_passes(t), outputs);
    ex.run_frame();
    Rendered r{ex.read(t.output), {}, ex.plan()};
    for (auto& e : extra) r.extra[e] = ex.read(e);
    return r;
  };
  Rendered direct = run("direct", true, {"gbuffer_normal"});
  EXPECT_EQ(non_finite_values(direct.out), 0u);
  EXPECT_EQ(non_finite_values(direct.extra["gbuffer_normal"]), 0u);
  EXPECT_GT(mean_channel(direct.out, 0), 0.1);
  EXPECT_EQ(non_finite_values(run("reference", true).out), 0u);
  Rendered unguarded = run("direct", false, {"gbuffer_normal"});
  EXPECT_GT(non_finite_values(unguarded.extra["gbuffer_normal"]), 0u) << "the NaN normal never reached the GPU";
  EXPECT_GT(non_finite_values(unguarded.out), 0u) << "without the guards the NaN normal should reach the image";
}

// Settings::world_offset moves the scene, its lights and the camera together: the same
// triangles cover the same pixels, G-buffer positions move by the offset, distances to the
// camera and the image stay the same (within float spacing at 10 km, ~1 mm).
TEST_F(Render, WorldOffsetMovesCameraWithScene) {
  Scene scene = lit_objects_scene(R"("sun": {"direction": [0.3, 1, 0.2], "irradiance": [2, 2, 2], "angular_radius_deg": 0})");
  const Vec3 offset{10000, 0, 10000};
  auto run = [&](Vec3 o) {
    const Technique& t = find_technique("direct");
    Settings s = apply_preset(t, "medium", Settings{});
    s.width = 64;
    s.height = 36;
    s.world_offset = o;
    Executor ex(gpu(), scene, s, make_passes(t), {t.output, "vbuffer", "gbuffer_position"});
    ex.run_frame();
    Rendered r{ex.read(t.output), {}, ex.plan()};
    for (const char* e : {"vbuffer", "gbuffer_position"}) r.extra[e] = ex.read(e);
    return r;
  };
  Rendered a = run({0, 0, 0}), b = run(offset);
  const FloatImage &va = a.extra["vbuffer"], &vb = b.extra["vbuffer"];
  const FloatImage &pa = a.extra["gbuffer_position"], &pb = b.extra["gbuffer_position"];
  size_t same = 0, covered = 0;
  double worst_pos = 0, worst_dist = 0;
  for (uint32_t y = 0; y < va.height; ++y)
    for (uint32_t x = 0; x < va.width; ++x) {
      if (va.at(x, y, 0) != vb.at(x, y, 0)) continue;
      ++same;
      if (va.at(x, y, 0) == 0) continue;  // sky
      ++covered;
      for (uint32_t c = 0; c < 3; ++c)
        worst_pos = std::max(worst_pos, std::abs(double(pb.at(x, y, c)) - offset[int(c)] - pa.at(x, y, c)));
      worst_dist = std::max(worst_dist, std::abs(double(pb.at(x, y, 3)) - pa.at(x, y, 3)));
    }
  std::printf("world offset: %zu of %u pixels on the same triangle, worst position error %.3g m, distance %.3g m\n",
              same, va.width * va.height, worst_pos, worst_dist);
  EXPECT_GT(covered, va.width * va.height / 2);
  EXPECT_GE(same, va.width * va.height * 98 / 100);
  EXPECT_LT(worst_pos, 0.02);   // the camera ray may meet the triangle a few mm apart
  EXPECT_LT(worst_dist, 0.02);  // the camera moved with the scene
  for (uint32_t c = 0; c < 3; ++c) EXPECT_NEAR(mean_channel(b.out, c), mean_channel(a.out, c), 0.01 * mean_channel(a.out, c));
  EXPECT_EQ(non_finite_values(b.out), 0u);
}

TEST_F(Render, RequestingOnlyTheVisibilityBufferCullsShading) {
  Scene scene = load_scene(scene_path("cornell.json"));
  Settings s = defaults_of("direct");
  Executor ex(gpu(), scene, s, make_passes(find_technique("direct")), {"vbuffer"});
  // The shading passes go for want of a reader; the shadow-mapped mode's passes are culled
  // before that, for want of a sun (cornell has none).
  std::vector<std::string> culled;
  for (auto& p : ex.plan().passes)
    if (!p.runs && p.reason != "scene lacks sun") {
      culled.push_back(p.name);
      EXPECT_EQ(p.reason, "outputs unused");
    }
  EXPECT_EQ(culled, (std::vector<std::string>{"gbuffer", "direct_lighting"}));
  ex.run_frame();
  EXPECT_THROW(ex.read("direct_light"), GraphError);  // culled: never allocated
}

class TouchesUndeclared final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    return {"rogue", PassKind::compute, {}, {}, {{"rogue_out", Access::write, {Format::rgba16_float}}}, false};
  }
  void record(RecordContext& ctx) override { (void)ctx.image("vbuffer"); }
};

TEST_F(Render, TouchingAnUndeclaredResourceFails) {
  Scene scene = load_scene(scene_path("cornell.json"));
  std::vector<std::unique_ptr<Pass>> passes;
  passes.push_back(std::make_unique<TouchesUndeclared>());
  Executor ex(gpu(), scene, Settings{}, std::move(passes), {"rogue_out"});
  try {
    ex.run_frame();
    FAIL() << "expected GraphError";
  } catch (const GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("pass 'rogue' touched resource 'vbuffer' it did not declare"),
              std::string::npos)
        << e.what();
  }
}

TEST(Devices, UnknownDeviceIsOneClearError) {
  try {
    Gpu::create({"no-such-device-xyz", false});
    FAIL();
  } catch (const GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("--device: expected an index or a name substring"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no-such-device-xyz"), std::string::npos);
  }
  auto list = Gpu::list_devices();
  ASSERT_FALSE(list.empty());
  EXPECT_EQ(std::count_if(list.begin(), list.end(), [](auto& d) { return d.is_default; }), 1);
}

}  // namespace
}  // namespace gib
