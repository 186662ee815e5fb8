// The direct-light modes (option direct_light, renderer/techniques/direct_light_modes.h): the
// graph runs the shared shadow passes only in the shadow_mapped mode; on a simple sunlit scene
// the shadow_mapped mode agrees with the traced one within what the shadow map's resolution,
// bias and PCF blur explain, a broken bias does not (the control); in the open, with sky light,
// the two modes agree to float precision (the same cosine directions, nothing to occlude).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using nlohmann::json;
constexpr uint32_t kW = 160, kH = 90;

// A 12 x 12 m grey floor and a 1.2 x 1.5 x 1.2 m grey box on it, a sun 56 degrees up with the
// real sun's angular radius (0.27 degrees, or `radius_deg`), seen from 4.5 m; with `box` false,
// the floor alone.
json sunlit_doc(bool box, double radius_deg = 0.27) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {12, 12}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"sun", {{"direction", {1.0, 1.8, 0.6}}, {"irradiance", {3, 3, 3}}, {"angular_radius_deg", radius_deg}}},
              {"camera", {{"position", {-1.5, 2.8, 3.0}}, {"target", {0.4, 0.2, -0.2}}, {"fov_y_deg", 50}}}};
  if (box)
    doc["objects"].push_back({{"name", "box"},
                              {"primitive", {{"type", "box"}, {"size", {1.2, 1.5, 1.2}}}},
                              {"material", "grey"},
                              {"transform", {{"translate", {0, 0.75, 0}}}}});
  return doc;
}

Settings mode_settings(const Technique& t, uint32_t mode, std::map<std::string, double> opts = {}) {
  Settings s;
  s.width = kW;
  s.height = kH;
  s = apply_preset(t, "medium", s);
  opts["direct_light"] = mode;
  return apply_options(t, s, opts);
}

Plan plan_of(const Technique& t, const Scene& scene, const Settings& s) {
  std::vector<PassDecl> decls;
  for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
  CompileOptions o;
  o.features = scene.features();
  o.outputs = {t.output};
  return compile(decls, o);
}

bool runs(const Plan& plan, const std::string& pass) {
  for (auto& p : plan.passes)
    if (p.name == pass) return p.runs;
  return false;
}

// The traced mode culls the shared shadow passes (nothing reads shadows_pcf); the shadow_mapped
// mode runs them in every technique that runs direct_lighting or deferred_lighting. gow-ragnarok
// keeps its own filter in both modes.
TEST(DirectLightModes, ShadowPassesRunOnlyWhenShadowMapped) {
  Scene scene = parse_scene(sunlit_doc(true), "sunlit-box");
  for (const char* name : {"direct", "deferred", "radiance-cache", "probe-volume", "voxel-clipmap"}) {
    const Technique& t = find_technique(name);
    for (uint32_t mode : {0u, 1u}) {
      Plan plan = plan_of(t, scene, mode_settings(t, mode));
      for (const char* pass : {"shadow_maps", "shadow_minmax", "shadows_pcf"})
        EXPECT_EQ(runs(plan, pass), mode == 1) << name << " direct_light " << mode << ": " << pass;
    }
  }
  const Technique& gow = find_technique("gow-ragnarok");
  for (uint32_t mode : {0u, 1u}) {
    Plan plan = plan_of(gow, scene, mode_settings(gow, mode));
    EXPECT_TRUE(runs(plan, "shadows_contact_hardening")) << "gow-ragnarok direct_light " << mode;
    EXPECT_FALSE(runs(plan, "shadows_pcf")) << "gow-ragnarok direct_light " << mode;
  }
  // Without a sun the shadow_mapped mode has no shadow pass to run.
  json doc = sunlit_doc(true);
  doc.erase("sun");
  doc["sky"] = {{"type", "constant"}, {"radiance", {1, 1, 1}}};
  Scene no_sun = parse_scene(doc, "no-sun");
  const Technique& direct = find_technique("direct");
  EXPECT_FALSE(runs(plan_of(direct, no_sun, mode_settings(direct, 1)), "shadow_maps"));
}

using test::GpuTest;
class DirectLightModesGpu : public GpuTest {};

FloatImage render_direct(Gpu& gpu, const Technique& t, const Scene& scene, const Settings& s) {
  Executor ex(gpu, scene, s, make_passes(t), {"direct_light"});
  ex.run_frame();
  return ex.read("direct_light");
}

struct Agreement {
  double rel_l1 = 0;  // sum |shadow_mapped - traced| / sum traced (red channel)
  double differ = 0;  // share of pixels differing by more than half the lit floor's level
  double shadow = 0;  // share of pixels the traced mode lights at under half that level
};
Agreement agreement(const FloatImage& traced, const FloatImage& mapped, double lit) {
  double diff = 0, sum = 0, far = 0, dark = 0;
  for (uint32_t y = 0; y < traced.height; ++y)
    for (uint32_t x = 0; x < traced.width; ++x) {
      const double a = traced.at(x, y, 0), b = mapped.at(x, y, 0);
      diff += std::fabs(a - b);
      sum += a;
      if (std::fabs(a - b) > 0.5 * lit) far += 1;
      if (a < 0.5 * lit) dark += 1;
    }
  const double n = double(traced.width) * traced.height;
  return {diff / sum, far / n, dark / n};
}

// Sun only (sky_rays 0): the traced mode's one cone-sampled shadow ray per pixel against the
// shadow_mapped mode's PCF of the cascaded shadow map (medium: 3 cascades of 1024 texels to
// 30 m, 16 taps over the sun seen from 2 m). Measured on lavapipe: 30 % of the pixels are under
// half the lit level (the cast shadow, about 3 %, and the faces turned from the sun), relative
// L1 0.0019, 0.03 % of pixels differing by half the lit level; the control 0.044 and 3.1 %.
// The modes can differ only along the shadow's outline, by less than a pixel (4.6 cm on the
// floor here): the traced penumbra is 1-spp noise over a 0.27-degree sun, PCF blurs over
// 2 m x tan(0.27 deg) = 9 mm plus a texel each side, the normal offset moves the edge by about
// a texel. Bounds: under 0.5 % of the pixels differing by more than half the lit level (a sixth
// of the cast shadow's area: a mode that misplaces more of it fails) and relative L1 under 1 %
// (a quarter of what losing the whole cast shadow costs: the control, a 5 m shadow bias that
// lights it, must miss both).
TEST_F(DirectLightModesGpu, ShadowMappedAgreesWithTracedOnASunlitBox) {
  Scene scene = parse_scene(sunlit_doc(true), "sunlit-box");
  const double sun_y = 1.8 / std::sqrt(1.0 + 1.8 * 1.8 + 0.36);
  const double lit = 0.5 * 3.0 * sun_y / 3.14159265358979;  // the open floor: albedo E cos / pi
  for (const char* name : {"direct", "deferred"}) {
    const Technique& t = find_technique(name);
    FloatImage traced = render_direct(gpu(), t, scene, mode_settings(t, 0, {{"sky_rays", 0}}));
    FloatImage mapped = render_direct(gpu(), t, scene, mode_settings(t, 1, {{"sky_rays", 0}}));
    FloatImage leak = render_direct(gpu(), t, scene, mode_settings(t, 1, {{"sky_rays", 0}, {"shadow_bias", 5}}));
    const Agreement good = agreement(traced, mapped, lit), bad = agreement(traced, leak, lit);
    std::printf("%-9s traced: %.3f of pixels under half the lit level; shadow_mapped vs traced: relative L1 "
                "%.4f, pixels differing > lit/2 %.4f; control (bias 5 m): %.4f, %.4f\n",
                name, good.shadow, good.rel_l1, good.differ, bad.rel_l1, bad.differ);
    EXPECT_GT(good.shadow, 0.1) << name << ": the scene's shadow is too small to test";
    EXPECT_LT(good.rel_l1, 0.01) << name;
    EXPECT_LT(good.differ, 0.005) << name;
    EXPECT_GT(bad.rel_l1, 0.01) << name << " (control)";
    EXPECT_GT(bad.differ, 0.005) << name << " (control)";
  }
}

// Sun and a gradient sky over the open floor, a sun of angular radius 0 (so the traced mode's
// cone sample is the sun's centre): nothing occludes, and the two modes sum the same sky
// radiance over the same cosine directions (the shadow_mapped mode draws and drops the traced
// mode's sun sample to keep them), so they agree to float rounding. With the 0.27-degree sun the
// traced sample tilts the sun's cosine by up to tan(34 deg) x 0.0047 rad = 3.2e-3 relative.
TEST_F(DirectLightModesGpu, UnoccludedSkyMatchesTracedSkyInTheOpen) {
  json doc = sunlit_doc(false, 0.0);
  doc["sky"] = {{"type", "gradient"}, {"radiance", {0.3, 0.5, 1.0}}, {"horizon", {1.0, 0.9, 0.8}}, {"ground", {0.2, 0.2, 0.2}}};
  Scene scene = parse_scene(doc, "open-floor");
  for (const char* name : {"direct", "deferred"}) {
    const Technique& t = find_technique(name);
    FloatImage traced = render_direct(gpu(), t, scene, mode_settings(t, 0));
    FloatImage mapped = render_direct(gpu(), t, scene, mode_settings(t, 1));
    double worst = 0;
    for (size_t i = 0; i < traced.pixels.size(); ++i)
      worst = std::max(worst, std::fabs(double(traced.pixels[i]) - mapped.pixels[i]) /
                                  std::max(1e-3, double(traced.pixels[i])));
    std::printf("%-9s open floor with sky: largest relative difference %.2e\n", name, worst);
    EXPECT_LT(worst, 1e-5) << name;
  }
}

// direct_light's alpha (direct_lighting): the share of the pixel's sky rays that met a surface,
// what a GI technique gathers its bounce over (voxel-clipmap's irradiance_shade). Under a sky,
// the open floor's rays meet nothing (0), the floor beside the box and the box's faces beside
// the floor some (k / 16 with 16 rays); the shadow_mapped mode traces none (0 everywhere).
TEST_F(DirectLightModesGpu, AlphaIsTheShareOfSkyRaysThatMetASurface) {
  json doc = sunlit_doc(true);
  doc["sky"] = {{"type", "constant"}, {"radiance", {1, 1, 1}}};
  Scene scene = parse_scene(doc, "sunlit-box-sky");
  const Technique& t = find_technique("direct");
  FloatImage traced = render_direct(gpu(), t, scene, mode_settings(t, 0, {{"sky_rays", 16}}));
  FloatImage mapped = render_direct(gpu(), t, scene, mode_settings(t, 1, {{"sky_rays", 16}}));
  uint32_t open = 0, partly = 0, off_grid = 0, mapped_nonzero = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const float a = traced.at(x, y, 3);
      open += a == 0.0f;
      partly += a > 0.0f && a <= 1.0f;
      off_grid += std::fabs(a * 16.0f - std::round(a * 16.0f)) > 1e-4f || a < 0.0f || a > 1.0f;
      mapped_nonzero += mapped.at(x, y, 3) != 0.0f;
    }
  std::printf("direct_light alpha, 16 sky rays: %u pixels 0, %u in (0, 1]; shadow_mapped: %u non-zero\n", open, partly,
              mapped_nonzero);
  EXPECT_GT(open, kW * kH / 4) << "the open floor and the sky meet nothing";
  EXPECT_GT(partly, kW * kH / 50) << "the floor beside the box and the box's faces meet the other";
  EXPECT_EQ(off_grid, 0u) << "a share of 16 rays";
  EXPECT_EQ(mapped_nonzero, 0u) << "the shadow_mapped mode traces no sky ray";
}

}  // namespace
}  // namespace gib
