// The cloth BRDF class's sheen lobe and the projected decals (renderer/shaders/include/brdf.glsl,
// decals.glsl): their CPU mirrors (renderer/scene/material_eval.h) on inputs with known answers,
// and the GPU's G-buffer albedo (the gbuffer pass of `direct`, the gbuffer_update pass of
// `deferred`) against the CPU mirror applied to the same pixels.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>

#include "renderer/graph/executor.h"
#include "renderer/scene/material_eval.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Vec3 dir(float theta, float phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(SheenLobe, CharlieDistributionIsNormalised) {
  // A microfacet distribution integrates to 1 against cos(theta_h) over the hemisphere.
  for (float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    const int n = 4096;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double theta = (i + 0.5) * (std::numbers::pi / 2) / n;
      sum += sheen_distribution(roughness, float(std::cos(theta))) * std::cos(theta) * std::sin(theta);
    }
    const double integral = sum * (std::numbers::pi / 2) / n * 2 * std::numbers::pi;
    EXPECT_NEAR(integral, 1.0, 2e-3) << "roughness " << roughness;
  }
}

TEST(SheenLobe, KnownValuesReciprocityAndHemisphere) {
  const Vec3 n{0, 0, 1};
  // Normal incidence both ways: h = n, sin(theta_h) = 0, D = 0 for any a < inf.
  EXPECT_EQ(sheen_lobe(1.0f, 0.5f, n, n, n), 0.0f);
  // Roughness 1 (a = 1): D = 3 sin(theta_h) / (2 pi); wi = wo at 60 degrees: h = wi,
  // sin = sqrt(3) / 2, V = 1 / (4 (1/2 + 1/2 - 1/4)) = 1/3.
  const Vec3 w = dir(kPi / 3, 0.4f);
  EXPECT_NEAR(sheen_lobe(0.5f, 1.0f, n, w, w), 0.5f * 3.0f * std::sqrt(3.0f) / 2 / (2 * kPi) / 3.0f, 1e-6f);
  // Reciprocal: f(wi, wo) = f(wo, wi).
  for (int i = 0; i < 64; ++i) {
    const Vec3 a = dir(0.02f + 1.5f * float(i % 8) / 8, 0.3f * float(i)), b = dir(0.05f + 1.4f * float(i / 8) / 8, -0.7f * float(i));
    EXPECT_NEAR(sheen_lobe(0.7f, 0.4f, n, a, b), sheen_lobe(0.7f, 0.4f, n, b, a), 1e-5f);
  }
  // Either direction below the surface: no reflection.
  EXPECT_EQ(sheen_lobe(1.0f, 0.5f, n, dir(2.0f, 0), w), 0.0f);
  EXPECT_EQ(sheen_lobe(1.0f, 0.5f, n, w, dir(2.0f, 0)), 0.0f);
}

TEST(SheenLobe, DirectionalAlbedoOfTheScenesClothStaysBelowOne) {
  // Energy: albedo + the lobe's directional albedo (integral of f cos over wi) stays below 1
  // for the cloth materials the committed scenes use, at every view angle.
  struct Cloth { float albedo_max, sheen, roughness; };
  for (Cloth c : {Cloth{0.5f, 0.35f, 0.5f}, Cloth{0.45f, 0.4f, 0.6f}}) {
    for (float view : {0.05f, 0.5f, 1.0f, 1.4f, 1.55f}) {
      const Vec3 n{0, 0, 1}, wo = dir(view, 0);
      const int nt = 256, np = 256;
      double sum = 0;
      for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
          const float t = (i + 0.5f) * (kPi / 2) / nt, p = (j + 0.5f) * 2 * kPi / np;
          sum += sheen_lobe(c.sheen, c.roughness, n, dir(t, p), wo) * std::cos(t) * std::sin(t);
        }
      const double lobe_albedo = sum * (kPi / 2) / nt * (2 * kPi) / np;
      EXPECT_LT(c.albedo_max + lobe_albedo, 1.0) << "view " << view << " lobe " << lobe_albedo;
    }
  }
}

GpuDecal decal(Vec3 position, Vec3 size, Vec3 rotation_deg, DecalShape shape, float opacity) {
  Scene s;
  Decal d;
  d.position = position;
  d.size = size;
  d.rotation_deg = rotation_deg;
  d.shape = shape;
  d.opacity = opacity;
  d.albedo = {0.2f, 0.4f, 0.6f};
  s.decals.push_back(d);
  return flatten(s, 0).decals.at(0);
}

TEST(Decals, WeightKnownAnswers) {
  const Vec3 up{0, 1, 0};
  // A floor decal: projects along -y (its local +z turned to +y), 2 x 1 m, 0.5 m deep.
  const GpuDecal d = decal({1, 0, 2}, {2, 1, 0.5f}, {-90, 0, 0}, DecalShape::disc, 0.8f);
  EXPECT_FLOAT_EQ(decal_weight(d, {1, 0, 2}, up), 0.8f) << "centre, facing: the opacity";
  EXPECT_EQ(decal_weight(d, {1, 0.3f, 2}, up), 0.0f) << "above the box";
  EXPECT_FLOAT_EQ(decal_weight(d, {1.9f, 0, 2}, up), 0.8f) << "inside the disc along x (half-width 1)";
  EXPECT_EQ(decal_weight(d, {1.9f, 0, 2.4f}, up), 0.0f) << "in the box's corner, outside the disc";
  EXPECT_EQ(decal_weight(d, {1, 0, 2}, {0, -1, 0}), 0.0f) << "a surface facing away";
  EXPECT_EQ(decal_weight(d, {1, 0, 2}, {1, 0, 0}), 0.0f) << "a wall along the projection (90 degrees)";
  const float c = 0.375f;  // cos between 60 and 75.5 degrees: fade (c - 0.25) * 4 = 0.5
  EXPECT_NEAR(decal_weight(d, {1, 0, 2}, {std::sqrt(1 - c * c), c, 0}), 0.8f * 0.5f, 1e-6f);
  const GpuDecal r = decal({0, 0, 0}, {1, 1, 1}, {0, 0, 0}, DecalShape::rect, 1.0f);
  EXPECT_EQ(decal_weight(r, {0.45f, 0.45f, 0}, {0, 0, 1}), 1.0f) << "a rect covers its corners";
  // Blending: albedo * k + c, decals in order.
  const std::vector<GpuDecal> both = {d, r};
  const Vec4 kc = decals_at(both, {1, 0, 2}, up);
  EXPECT_NEAR(kc.w, 0.2f, 1e-6f);
  const Vec3 a = decal_blend({1, 1, 1}, kc);
  EXPECT_NEAR(a.x, 0.2f + 0.8f * 0.2f, 1e-6f);
  EXPECT_NEAR(a.z, 0.2f + 0.8f * 0.6f, 1e-6f);
  EXPECT_EQ(decals_at({}, {0, 0, 0}, up).w, 1.0f);
}

// The G-buffer albedo of a technique on features_zoo (two decals: a stain on the ground, a sign
// on the cloth cushion) against the same scene without decals, blended on the CPU.
class DecalsGpu : public test::GpuTest {};

std::map<std::string, FloatImage> gbuffer(Gpu& gpu, const Scene& scene, const std::string& technique) {
  const Technique& t = find_technique(technique);
  Settings s;
  s.width = 96;
  s.height = 64;
  s = apply_preset(t, "low", s);
  const std::vector<std::string> names = {"gbuffer_albedo", "gbuffer_position", "gbuffer_normal"};
  Executor ex(gpu, scene, s, make_passes(t), names);
  ex.run_frame();
  std::map<std::string, FloatImage> out;
  for (auto& n : names) out[n] = ex.read(n);
  return out;
}

TEST_F(DecalsGpu, GbufferAlbedoIsTheCpuMirrorsBlend) {
  const Scene with = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/features_zoo.json");
  ASSERT_FALSE(with.decals.empty());
  Scene without = with;
  without.decals.clear();
  const std::vector<GpuDecal> decals = flatten(with, 0).decals;
  for (const char* technique : {"direct", "deferred"}) {
    auto a = gbuffer(gpu(), with, technique), b = gbuffer(gpu(), without, technique);
    const FloatImage &albedo = a["gbuffer_albedo"], &plain = b["gbuffer_albedo"], &pos = a["gbuffer_position"],
                     &nrm = a["gbuffer_normal"];
    size_t covered = 0, off = 0, untouched_changed = 0;
    for (uint32_t y = 0; y < albedo.height; ++y)
      for (uint32_t x = 0; x < albedo.width; ++x) {
        if (pos.at(x, y, 3) == 0.0f) continue;  // sky
        const Vec4 kc = decals_at(decals, {pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2)},
                                  {nrm.at(x, y, 0), nrm.at(x, y, 1), nrm.at(x, y, 2)});
        const Vec3 base{plain.at(x, y, 0), plain.at(x, y, 1), plain.at(x, y, 2)};
        if (kc.w == 1.0f) {
          for (uint32_t c = 0; c < 4; ++c)
            untouched_changed += std::bit_cast<uint32_t>(albedo.at(x, y, c)) != std::bit_cast<uint32_t>(plain.at(x, y, c));
          continue;
        }
        ++covered;
        const Vec3 e = decal_blend(base, kc);
        for (uint32_t c = 0; c < 3; ++c) off += std::fabs(albedo.at(x, y, c) - e[c]) > 2e-3f;  // half-float albedo
        EXPECT_EQ(albedo.at(x, y, 3), plain.at(x, y, 3)) << "the sheen channel is not a decal's";
      }
    EXPECT_GT(covered, 50u) << technique;
    // A pixel on a decal's edge (mask, box or fade boundary within float rounding of the CPU's)
    // may fall on the other side: at most 1 % of the covered pixels.
    EXPECT_LE(off, covered / 100 + 1) << technique << ": " << off << " of " << covered << " covered pixels";
    EXPECT_LE(untouched_changed, covered / 100 + 1) << technique << ": albedo changed where the CPU sees no decal";
  }
}

}  // namespace
}  // namespace gib
