// The glossy BRDF class (renderer/shaders/include/brdf.glsl, CPU mirror material_eval.h):
// GGX's normalisations, the white metal's directional albedo against closed forms (roughness 1)
// and quadrature, the energy bound of the layered split, the sampler and its density against
// quadrature (Monte Carlo within its error), the device against the CPU mirror, the scene key,
// and the path tracer's glossy furnace and reflection AOV on the device.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/material_eval.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"
#include "tests/glossy_brdf_test_shared.h"
#include "tests/gpu_fixture.h"
#include "tests/test_rng.h"

namespace gib {
namespace {

using namespace glossy_brdf_test;
constexpr double kPi = std::numbers::pi;
const Vec3 kN{0, 0, 1};

Vec3 dir(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
}

// Integral over the hemisphere of g(w) (midpoint rule in theta, phi).
template <class F>
double hemisphere(F g, int steps = 512) {
  const double dt = kPi / 2 / steps, dp = kPi / steps;
  double sum = 0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      const double t = (i + 0.5) * dt, p = (j + 0.5) * dp;
      sum += g(dir(t, p)) * std::sin(t);
    }
  return sum * dt * dp;
}

TEST(GlossyBrdf, GgxDistributionAndVisibleNormalsAreNormalised) {
  for (float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    const float a = ggx_alpha(roughness);
    // integral of D(h) n.h over the hemisphere = 1
    EXPECT_NEAR(hemisphere([&](Vec3 h) { return ggx_d(a, h.z) * h.z; }, 1024), 1.0, 2e-3) << roughness;
    // integral of G1(v) max(0, v.h) D(h) over h = n.v (the visible normals' density integrates to 1)
    for (float view : {0.0f, 0.7f, 1.3f}) {
      const Vec3 v = dir(view, 0.3);
      const double s = hemisphere([&](Vec3 h) { return ggx_g1(a, v.z) * std::fmax(0.0f, dot(v, h)) * ggx_d(a, h.z); }, 1024);
      EXPECT_NEAR(s, v.z, 2e-3) << "roughness " << roughness << " view " << view;
    }
  }
}

TEST(GlossyBrdf, WhiteMetalDirectionalAlbedoKnownValues) {
  // Roughness 1 (a = 1): D = 1/pi, V = 1 / (2 (nl + nv)), so E(mu) = integral over mu_l of
  // mu_l / (mu_l + mu) = 1 - mu ln((1 + mu) / mu): 1 - ln 2 = 0.30685 at normal incidence.
  for (double mu : {1.0, 0.5, 0.1}) {
    const double closed = 1 - mu * std::log((1 + mu) / mu);
    EXPECT_NEAR(ggx_directional_albedo(1.0f, float(mu), 1024), closed, 1e-3) << "mu " << mu;
  }
  EXPECT_NEAR(ggx_directional_albedo(1.0f, 1.0f, 1024), 1.0 - std::log(2.0), 5e-4);
  // Near-mirror: nothing is masked at normal incidence, E -> 1 (quadrature at 4096 steps).
  EXPECT_NEAR(ggx_directional_albedo(0.1f, 1.0f, 2048), 1.0, 5e-3);
  // Energy: E <= 1 at every view angle, and at normal incidence it falls with roughness
  // (single scattering loses more between rougher microfacets).
  for (float mu : {1.0f, 0.6f, 0.2f, 0.05f}) {
    double last = 2;
    for (float r : {0.3f, 0.45f, 0.6f, 0.8f, 1.0f}) {
      const double e = ggx_directional_albedo(r, mu, 512);
      EXPECT_LE(e, 1.0 + 2e-3) << "roughness " << r << " mu " << mu;
      if (mu == 1.0f) {
        EXPECT_LT(e, last) << "roughness " << r;
      }
      last = e;
    }
  }
}

// Monte Carlo estimate of the directional albedo integral of (spec + diffuse) cos through the
// sampler and its pdf (the path tracer's estimator), with its standard error.
struct Estimate {
  Vec3 mean, err;
};
Estimate sampled_albedo(Vec3 wo, Vec3 albedo, float roughness, float metalness, int samples, uint64_t seed) {
  test::Rng rng(seed);
  const float p_spec = glossy_spec_probability(kN, wo, albedo, metalness);
  double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
  for (int i = 0; i < samples; ++i) {
    const float u0 = rng.uniform(), u1 = rng.uniform(), pick = rng.uniform();
    const Vec3 wi = glossy_sample(kN, wo, roughness, p_spec, u0, u1, pick);
    const float pdf = glossy_pdf(kN, wo, wi, roughness, p_spec);
    if (!(pdf > 0.0f) || wi.z <= 0.0f) continue;
    const GlossyLobes f = glossy_eval(kN, wo, wi, albedo, roughness, metalness);
    const Vec3 w = (f.spec + f.diffuse) * (wi.z / pdf);
    for (int c = 0; c < 3; ++c) s[c] += w[c], s2[c] += double(w[c]) * w[c];
  }
  Estimate e;
  for (int c = 0; c < 3; ++c) {
    const double m = s[c] / samples, var = s2[c] / samples - m * m;
    e.mean[c] = float(m);
    e.err[c] = float(std::sqrt(std::fmax(var, 0.0) / samples));
  }
  return e;
}

Vec3 quadrature_albedo(Vec3 wo, Vec3 albedo, float roughness, float metalness, int steps = 512) {
  const double dt = kPi / 2 / steps, dp = kPi / steps;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      const double t = (i + 0.5) * dt;
      const Vec3 wi = dir(t, (j + 0.5) * dp);
      const GlossyLobes f = glossy_eval(kN, wo, wi, albedo, roughness, metalness);
      for (int c = 0; c < 3; ++c) sum[c] += double(f.spec[c] + f.diffuse[c]) * wi.z * std::sin(t);
    }
  return {float(sum[0] * dt * dp), float(sum[1] * dt * dp), float(sum[2] * dt * dp)};
}

TEST(GlossyBrdf, SamplerAndDensityMatchQuadratureWithinMonteCarloError) {
  struct M { Vec3 albedo; float roughness, metalness; };
  const M materials[] = {{{1, 1, 1}, 1.0f, 1.0f}, {{1, 1, 1}, 0.5f, 1.0f}, {{1, 1, 1}, 0.3f, 0.0f},
                         {{0.9f, 0.6f, 0.2f}, 0.6f, 1.0f}, {{0.2f, 0.5f, 0.8f}, 0.4f, 0.5f}};
  int k = 0;
  for (const M& m : materials)
    for (float view : {0.1f, 0.8f, 1.4f}) {
      const Vec3 wo = dir(view, 0.2);
      const Vec3 q = quadrature_albedo(wo, m.albedo, m.roughness, m.metalness);
      const Estimate e = sampled_albedo(wo, m.albedo, m.roughness, m.metalness, 200000, 11 + k++);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(e.mean[c], q[c], 4 * e.err[c] + 2e-3)
            << "roughness " << m.roughness << " metalness " << m.metalness << " view " << view << " channel " << c;
        // The layered split's energy bound: the directional albedo is at most 1.
        EXPECT_LE(q[c], 1.0f + 2e-3f);
      }
    }
}

TEST(GlossyBrdf, EnergyBoundOfTheLayerForWhiteInputs) {
  // albedo 1: F E_ggx + (1 - m)(1 - F) <= 1 at every view angle, roughness and metalness.
  // (Midpoint quadrature resolves the lobe from roughness 0.3 on; smoother lobes are checked by
  // the sampler test's Monte Carlo.)
  for (float m : {0.0f, 0.5f, 1.0f})
    for (float r : {0.3f, 0.7f, 1.0f})
      for (float view : {0.0f, 0.9f, 1.5f}) {
        const Vec3 q = quadrature_albedo(dir(view, 0), {1, 1, 1}, r, m);
        EXPECT_LE(q.x, 1.0f + 3e-3f) << "metalness " << m << " roughness " << r << " view " << view;
      }
  // Smooth lobes by Monte Carlo (each sample's weight f cos / pdf): within its error of <= 1.
  for (float m : {0.0f, 1.0f})
    for (float view : {0.0f, 0.9f, 1.5f}) {
      const Estimate e = sampled_albedo(dir(view, 0), {1, 1, 1}, 0.05f, m, 100000, 5);
      EXPECT_LE(e.mean.x, 1.0f + 4 * e.err.x) << "metalness " << m << " view " << view;
      EXPECT_GT(e.mean.x, 0.9f) << "a near-mirror loses little: metalness " << m << " view " << view;
    }
  // Known values at normal incidence: F = F0, the diffuse layer gets (1 - m)(1 - F0) albedo / pi.
  const GlossyLobes f = glossy_eval(kN, kN, dir(0.5, 1.0), {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f);
  EXPECT_NEAR(f.diffuse.x, 0.96 * 0.5 / kPi, 1e-6);
  const float nl = float(std::cos(0.5));
  EXPECT_NEAR(f.spec.x, 0.04 * (1 / kPi) * 0.5 / (nl + 1.0), 1e-6);  // a = 1: D = 1/pi, V = 1/(2(nl+nv))
  EXPECT_EQ(glossy_eval(kN, kN, dir(2.0, 0), {1, 1, 1}, 0.5f, 0.0f).spec.x, 0.0f) << "below the surface";
  EXPECT_EQ(glossy_spec_probability(kN, kN, {1, 1, 1}, 1.0f), 1.0f) << "a metal has no diffuse lobe";
}

class GlossyBrdfGpu : public test::GpuTest {};

TEST_F(GlossyBrdfGpu, DeviceMatchesCpuMirror) {
  test::Rng rng(23);
  std::vector<GlossyBrdfTestQuery> q(4096);
  auto unit = [&] { return normalize({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}); };
  for (size_t i = 0; i < q.size(); ++i) {
    GlossyBrdfTestQuery& x = q[i];
    const Vec3 n = unit();
    Vec3 wo = unit(), wi = unit();
    if (dot(wo, n) < 0) wo = -wo;
    if (i % 5 != 0 && dot(wi, n) < 0) wi = -wi;  // a fifth may lie below
    for (int c = 0; c < 3; ++c) x.n[c] = n[c], x.wo[c] = wo[c], x.wi[c] = wi[c], x.albedo[c] = rng.uniform();
    x.roughness = i % 7 == 0 ? 0.0f : rng.uniform();
    x.metalness = i % 3 == 0 ? 1.0f : rng.uniform();
    x.u0 = rng.uniform(), x.u1 = rng.uniform(), x.pick = rng.uniform(), x.pad = 0;
  }
  static_assert(sizeof(GlossyBrdfTestQuery) == GLOSSY_BRDF_TEST_QUERY_FLOATS * 4);
  static_assert(sizeof(GlossyBrdfTestOut) == GLOSSY_BRDF_TEST_OUT_FLOATS * 4);
  auto in = gpu().create_buffer(q.size() * sizeof(GlossyBrdfTestQuery), BufferUsage::storage, "glossy_brdf_test.queries");
  gpu().upload(*in, q.data(), q.size() * sizeof(GlossyBrdfTestQuery));
  auto out = gpu().create_buffer(q.size() * sizeof(GlossyBrdfTestOut), BufferUsage::storage, "glossy_brdf_test.out");
  ComputePipelineDesc desc{"glossy_brdf_test.comp",
                           {{GLOSSY_BRDF_TEST_BINDING_QUERIES, DescriptorKind::storage_buffer},
                            {GLOSSY_BRDF_TEST_BINDING_OUT, DescriptorKind::storage_buffer}},
                           sizeof(GlossyBrdfTestPush)};
  auto pipeline = gpu().compute_pipeline(desc);
  const Bind binds[] = {{GLOSSY_BRDF_TEST_BINDING_QUERIES, in.get()}, {GLOSSY_BRDF_TEST_BINDING_OUT, out.get()}};
  const GlossyBrdfTestPush push{uint32_t(q.size())};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch((uint32_t(q.size()) + GLOSSY_BRDF_TEST_WORKGROUP_SIZE - 1) / GLOSSY_BRDF_TEST_WORKGROUP_SIZE);
  gpu().submit(std::move(cmd));
  std::vector<GlossyBrdfTestOut> o(q.size());
  gpu().download(*out, o.data(), o.size() * sizeof(GlossyBrdfTestOut));

  // Relative to the value's size (D reaches 1e5 at the smallest roughness), a few float ulps
  // of the inputs through sqrt, division and the fifth power.
  auto close = [](float cpu, float gpu_v) { return std::fabs(cpu - gpu_v) <= 2e-4f * std::fmax(1.0f, std::fabs(cpu)); };
  size_t below = 0, worst_i = 0;
  float worst = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const GlossyBrdfTestQuery& x = q[i];
    const Vec3 n{x.n[0], x.n[1], x.n[2]}, wo{x.wo[0], x.wo[1], x.wo[2]}, wi{x.wi[0], x.wi[1], x.wi[2]};
    const Vec3 albedo{x.albedo[0], x.albedo[1], x.albedo[2]};
    const GlossyLobes f = glossy_eval(n, wo, wi, albedo, x.roughness, x.metalness);
    const float p_spec = glossy_spec_probability(n, wo, albedo, x.metalness);
    const float pdf = glossy_pdf(n, wo, wi, x.roughness, p_spec);
    const Vec3 s = glossy_sample(n, wo, x.roughness, p_spec, x.u0, x.u1, x.pick);
    const Vec3 h = ggx_sample_vndf(n, wo, ggx_alpha(x.roughness), x.u0, x.u1);
    below += dot(wi, n) <= 0;
    const float pairs[][2] = {{f.spec.x, o[i].spec[0]},       {f.spec.y, o[i].spec[1]},       {f.spec.z, o[i].spec[2]},
                              {f.diffuse.x, o[i].diffuse[0]}, {f.diffuse.y, o[i].diffuse[1]}, {f.diffuse.z, o[i].diffuse[2]},
                              {p_spec, o[i].p_spec},          {pdf, o[i].pdf},                {s.x, o[i].sampled[0]},
                              {s.y, o[i].sampled[1]},         {s.z, o[i].sampled[2]},         {h.x, o[i].vndf[0]},
                              {h.y, o[i].vndf[1]},            {h.z, o[i].vndf[2]}};
    for (auto& p : pairs) {
      const float d = std::fabs(p[0] - p[1]) / std::fmax(1.0f, std::fabs(p[0]));
      if (d > worst) worst = d, worst_i = i;
      EXPECT_TRUE(close(p[0], p[1])) << "query " << i << ": cpu " << p[0] << " gpu " << p[1];
    }
  }
  std::printf("glossy BRDF: %zu queries (%zu below the surface), worst relative difference %.3g (query %zu)\n",
              q.size(), below, worst, worst_i);
  EXPECT_GT(below, q.size() / 20);
}

TEST(GlossyBrdf, SceneKeyAndErrors) {
  auto parse = [](const std::string& m) {
    return parse_scene(nlohmann::json::parse(R"({"materials": {"m": )" + m + R"(},
      "objects": [{"primitive": {"type": "sphere", "radius": 1}, "material": "m"}],
      "camera": {"position": [0, 0, 4], "target": [0, 0, 0]}})"), "inline.json");
  };
  const Scene s = parse(R"({"brdf": "glossy", "albedo": [1, 1, 1], "metalness": 1, "roughness": 0.3})");
  EXPECT_EQ(s.materials[0].brdf, BrdfKind::glossy);
  EXPECT_TRUE(s.features().has(Feature::glossy));
  EXPECT_EQ(flatten(s, 0).materials[0].brdf, uint32_t(BrdfKind::glossy));
  EXPECT_FALSE(parse(R"({"albedo": [1, 1, 1]})").features().has(Feature::glossy));
  EXPECT_EQ(flatten(parse(R"({"brdf": "cloth", "sheen": 0.5})"), 0).materials[0].brdf, 0u);
  auto error = [&](const std::string& m) {
    try {
      parse(m);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error(R"({"brdf": "glossy", "translucency": 0.5})").find("/materials/m/translucency: expected 0 for brdf \"glossy\""),
            std::string::npos)
      << error(R"({"brdf": "glossy", "translucency": 0.5})");
  EXPECT_NE(error(R"({"brdf": "glossy", "sheen": 0.5})").find("no sheen for brdf \"glossy\""), std::string::npos);
  EXPECT_NE(error(R"({"brdf": "glosy"})").find("/materials/m/brdf"), std::string::npos);
}

// The path tracer on the device: a white metal sphere (roughness 1) and a white dielectric
// (roughness 0.5) under a constant sky of radiance 1 with nothing else in view. Each sphere
// is convex, so each pixel is the directional albedo at its view angle: the metal's centre
// pixel E(1) = 1 - ln 2 (closed form), the dielectric within [E_ggx, 1]. The reflection AOV
// holds all of the metal's light (no diffuse lobe) and only the specular share of the dielectric's.
class GlossyFurnace : public test::GpuTest {};

TEST_F(GlossyFurnace, PathTracerMeetsTheClosedFormAndTheEnergyBound) {
  const Scene scene = parse_scene(nlohmann::json::parse(R"({
    "materials": {"metal": {"brdf": "glossy", "albedo": [1, 1, 1], "metalness": 1, "roughness": 1},
                  "dielectric": {"brdf": "glossy", "albedo": [1, 1, 1], "metalness": 0, "roughness": 0.5}},
    "objects": [{"primitive": {"type": "sphere", "radius": 1, "segments": 64}, "material": "metal", "transform": {"translate": [-1.6, 0, 0]}},
                {"primitive": {"type": "sphere", "radius": 1, "segments": 64}, "material": "dielectric", "transform": {"translate": [1.6, 0, 0]}}],
    "sky": {"type": "constant", "radiance": [1, 1, 1]},
    "camera": {"position": [0, 0, 40], "target": [0, 0, 0], "fov_y_deg": 6}})"), "inline.json");
  const Technique& t = find_technique("reference");
  Settings s;
  s.width = 64;
  s.height = 32;
  s = apply_preset(t, "ultra", s);
  s.params<ReferenceSettings>().spp_per_frame = 64;
  Executor ex(gpu(), scene, s, make_passes(t), {"radiance", "reflection", "direct"});
  for (int f = 0; f < 4; ++f) ex.run_frame();  // 256 spp
  const FloatImage rad = ex.read("radiance"), refl = ex.read("reflection");
  // The spheres' centres: the camera is 40 m away (nearly orthographic); a 3x3 block at each
  // centre sees mu >= 0.99.
  auto block = [&](const FloatImage& im, uint32_t cx) {
    double sum = 0;
    for (uint32_t y = 15; y <= 17; ++y)
      for (uint32_t x = cx - 1; x <= cx + 1; ++x) sum += im.at(x, y, 1);
    return sum / 9;
  };
  const double metal = block(rad, 32 - 12), dielectric = block(rad, 32 + 12);
  std::printf("glossy furnace: metal centre %.4f (1 - ln 2 = %.4f), dielectric centre %.4f\n", metal,
              1 - std::log(2.0), dielectric);
  EXPECT_NEAR(metal, 1 - std::log(2.0), 0.01);
  EXPECT_LE(dielectric, 1.0 + 0.005);
  EXPECT_GE(dielectric, 0.96);
  EXPECT_NEAR(block(refl, 32 - 12), metal, 1e-4) << "a metal reflects everything through its specular lobe";
  const double dielectric_refl = block(refl, 32 + 12);
  EXPECT_GT(dielectric_refl, 0.02);
  EXPECT_LT(dielectric_refl, 0.08) << "a dielectric's specular layer reflects about F0 = 0.04 at normal incidence";
  double worst = 0;
  for (uint32_t y = 0; y < rad.height; ++y)
    for (uint32_t x = 0; x < rad.width; ++x) worst = std::fmax(worst, rad.at(x, y, 0));
  EXPECT_LE(worst, 1.0 + 0.05) << "no pixel above the sky (per-pixel noise at 256 spp)";
}

}  // namespace
}  // namespace gib
