// The AOV contract (renderer/techniques/aov.h) checked on every technique: direct +
// indirect_diffuse == radiance where a technique declares both; on five one-source scenes
// (sun, sky, point light, emissive quad, sky on a curved mesh) each technique's `direct` agrees with the reference's
// within their noise; on a sky-lit plane both AOVs equal the analytic values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/aov.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;
using nlohmann::json;

constexpr uint32_t kW = 32, kH = 18;

// A 20 x 20 m grey floor seen straight from above (every pixel is floor), plus `extra` keys.
Scene floor_scene(const json& extra) {
  json doc = {{"materials", {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}, {"lamp", {{"albedo", {0, 0, 0}}, {"emissive", {4, 4, 4}}}}}},
              {"objects", json::array({{{"name", "floor"},
                                        {"primitive", {{"type", "quad"}, {"size", {20, 20}}, {"facing", "+y"}}},
                                        {"material", "grey"}}})},
              {"camera", {{"position", {0, 1, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fov_y_deg", 50}}}};
  for (auto& [k, v] : extra.items()) {
    if (k == "objects")
      for (auto& o : v) doc["objects"].push_back(o);
    else
      doc[k] = v;
  }
  return parse_scene(doc, "aov-contract");
}

struct OneSource {
  const char* name;
  json extra;
};
std::vector<OneSource> one_source_scenes() {
  return {
      {"sun", {{"sun", {{"direction", {0.3, 1.0, 0.2}}, {"irradiance", {3, 3, 3}}, {"angular_radius_deg", 0.27}}}}},
      {"sky", {{"sky", {{"type", "constant"}, {"radiance", {1.5, 1.5, 1.5}}}}}},
      {"point", {{"lights", json::array({{{"type", "point"}, {"position", {0.3, 0.8, 0.2}}, {"intensity", {2, 2, 2}},
                                          {"range", 10}}})}}},
      // A 6 x 6 m emissive panel 2 m up, facing the floor (the camera, 1 m up, is under it).
      {"emissive_quad",
       {{"objects", json::array({{{"name", "panel"},
                                  {"primitive", {{"type", "quad"}, {"size", {6, 6}}, {"facing", "-y"}}},
                                  {"material", "lamp"},
                                  {"transform", {{"translate", {0, 2, 0}}}}}})}}},
      // Sky on a coarse (6-segment) smooth-shaded sphere: interpolated normals lean past the faces,
      // so rays that leave along them start inside the mesh unless they leave as the reference's
      // do (without the face-normal mirror: direct 0.674 vs 0.716, 12 sigma; with it: 0.717).
      {"sky_sphere",
       {{"sky", {{"type", "constant"}, {"radiance", {1.5, 1.5, 1.5}}}},
        {"objects", json::array({{{"name", "ball"},
                                  {"primitive", {{"type", "sphere"}, {"radius", 0.4}, {"segments", 6}}},
                                  {"material", "grey"},
                                  {"transform", {{"translate", {0, 0.4, 0}}}}}})}}},
  };
}

// Mean over frames 1..frames of the given resources (one executor, one seed).
// `supersample` > 1 renders at that many times the size and box-filters down, so a technique
// that shades pixel centres integrates the pixel footprint the way the reference's jittered
// camera rays do (the test compares light paths, not pixel filters).
std::map<std::string, FloatImage> render_mean(Gpu& gpu, const Scene& scene, const std::string& technique,
                                              const std::vector<std::string>& resources, uint32_t frames,
                                              uint32_t seed, const std::string& preset = "medium",
                                              uint32_t supersample = 1) {
  const Technique& t = find_technique(technique);
  Settings s;
  s.width = kW * supersample;
  s.height = kH * supersample;
  s.seed = seed;
  s = apply_preset(t, preset, s);
  if (s.has_params<ReferenceSettings>()) ref(s).spp_per_frame = 16;
  Executor ex(gpu, scene, s, make_passes(t), resources);
  // The reference accumulates over frames itself: its last frame is the mean.
  const bool accumulates = technique == "reference";
  std::map<std::string, FloatImage> sum;
  for (uint32_t f = 0; f < frames; ++f) {
    ex.run_frame();
    if (accumulates && f + 1 < frames) continue;
    for (auto& r : resources) {
      FloatImage img = ex.read(r);
      if (!sum.count(r)) {
        sum[r] = std::move(img);
        continue;
      }
      for (size_t i = 0; i < img.pixels.size(); ++i) sum[r].pixels[i] += img.pixels[i];
    }
  }
  const float scale = 1.0f / float(accumulates ? 1 : frames) / float(supersample * supersample);
  for (auto& [r, img] : sum) {
    FloatImage down(kW, kH, img.channels);
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x)
        for (uint32_t c = 0; c < img.channels; ++c) down.at(x / supersample, y / supersample, c) += img.at(x, y, c) * scale;
    img = std::move(down);
  }
  return sum;
}

// The mean of the RGB channels over the image.
double image_mean(const FloatImage& img) {
  double s = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x)
      for (uint32_t c = 0; c < 3; ++c) s += img.at(x, y, c);
  return s / (3.0 * img.width * img.height);
}

// Variance of the image mean, estimated from two independent renders a, b (per-pixel
// differences, pixels treated as independent): var(mean a) ~ mean((a - b)^2) / 2 / N.
double mean_variance(const FloatImage& a, const FloatImage& b) {
  double s = 0;
  size_t n = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      double d = 0;
      for (uint32_t c = 0; c < 3; ++c) d += (a.at(x, y, c) - b.at(x, y, c)) / 3.0;
      s += d * d;
      ++n;
    }
  return s / 2.0 / double(n) / double(n);
}

class AovContract : public GpuTest {};

TEST_F(AovContract, EveryTechniqueDeclaresOnlyContractNamesAndRadianceIsItsOutput) {
  for (const Technique& t : techniques()) {
    EXPECT_EQ(contract_resource(t, "radiance"), t.output) << t.name;
    for (auto& [aov, res] : t.contract_aovs) {
      bool known = false;
      for (auto a : kContractAovs) known |= a == aov;
      EXPECT_TRUE(known) << t.name << " declares '" << aov << "', not an AOV of the contract";
      EXPECT_FALSE(res.empty()) << t.name;
    }
  }
  EXPECT_EQ(contract_aov_names(find_technique("reference")),
            (std::vector<std::string>{"radiance", "direct", "indirect_diffuse", "reflection"}));
}

// Per pixel, to float precision: direct + indirect_diffuse == radiance (the cornell box has
// every light type but the sky and sun: emissive quad, point light; the thin-wall scene sun
// and sky), for every technique that declares both; direct == radiance where a technique
// declares only direct (it has no indirect light).
TEST_F(AovContract, DirectPlusIndirectIsRadiancePerPixel) {
  for (const char* file : {"cornell.json", "thin_wall_005.json"}) {
    Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + file);
    for (const Technique& t : techniques()) {
      std::vector<std::string> names = contract_aov_names(t, scene.features());
      std::vector<std::string> res;
      for (auto& a : names) res.push_back(contract_resource(t, a));
      // Three frames: temporal techniques past their first frame; the reference at 48 spp.
      Executor ex(gpu(), scene,
                  [&] {
                    Settings s;
                    s.width = kW;
                    s.height = kH;
                    return apply_preset(t, "low", s);
                  }(),
                  make_passes(t), res);
      for (int f = 0; f < 3; ++f) ex.run_frame();
      std::map<std::string, FloatImage> img;
      for (size_t i = 0; i < names.size(); ++i) img[names[i]] = ex.read(res[i]);
      const FloatImage& r = img.at("radiance");
      ASSERT_TRUE(img.count("direct")) << t.name << " declares no direct AOV";
      const FloatImage& d = img.at("direct");
      bool has_indirect = img.count("indirect_diffuse") > 0;
      double worst = 0, peak = 0;
      for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x)
          for (uint32_t c = 0; c < 3; ++c) {
            double sum = d.at(x, y, c) + (has_indirect ? img.at("indirect_diffuse").at(x, y, c) : 0.0f);
            double rv = r.at(x, y, c);
            worst = std::max(worst, std::abs(sum - rv) / std::max(1.0, std::abs(rv)));
            peak = std::max(peak, rv);
          }
      std::printf("%-16s %-14s max |direct + indirect - radiance| / max(1, radiance) = %.3g (peak %.3g)\n", file,
                  t.name.c_str(), worst, peak);
      EXPECT_GT(peak, 0.0) << file << " " << t.name << ": a black image proves nothing";
      EXPECT_LE(worst, 1e-5) << file << " " << t.name;
    }
  }
}

// Each one-source scene: every technique's `direct` image mean agrees with the reference's
// `direct` within 4 standard errors of the two (each estimated from two seeds). One test per
// scene, so each stays well under a minute on two cores.
class AovContractOneSource : public GpuTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(AovContractOneSource, DirectAgreesWithReference) {
  const OneSource src = one_source_scenes().at(GetParam());
  Scene scene = floor_scene(src.extra);
  const Technique& reft = find_technique("reference");
  std::string ref_res = contract_resource(reft, "direct");
  FloatImage ra = render_mean(gpu(), scene, "reference", {ref_res}, 4, 1)[ref_res];
  FloatImage rb = render_mean(gpu(), scene, "reference", {ref_res}, 4, 1001)[ref_res];
  double ref_mean = image_mean(ra), ref_var = mean_variance(ra, rb);
  EXPECT_GT(ref_mean, 0.01) << src.name << ": the source must light the floor";
  for (const Technique& t : techniques()) {
    if (t.name == "reference") continue;
    std::string res = contract_resource(t, "direct");
    if (res.empty()) continue;
    // Only `direct` is requested: the graph culls every pass it does not need.
    FloatImage a = render_mean(gpu(), scene, t.name, {res}, 8, 1, "medium", 4)[res];
    FloatImage b = render_mean(gpu(), scene, t.name, {res}, 8, 1001, "medium", 4)[res];
    double mean = image_mean(a), var = mean_variance(a, b);
    // 4 sigma, plus 1e-4 of the mean for float arithmetic (sums in another order, the GPU's
    // approximate transcendentals: an H100 reads 5e-5 apart on the noiseless sun floor).
    double tol = 4.0 * std::sqrt(var + ref_var) + 1e-4 * ref_mean;
    std::printf("%-13s %-14s direct mean %.5f, reference %.5f (diff %+.5f, tolerance %.5f = 4 sigma)\n", src.name,
                t.name.c_str(), mean, ref_mean, mean - ref_mean, tol);
    EXPECT_NEAR(mean, ref_mean, tol) << src.name << " " << t.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AovContractOneSource, ::testing::Range<size_t>(0, one_source_scenes().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::string(one_source_scenes().at(info.param).name);
                         });

// A grey plane (albedo 0.5) under a constant sky (radiance 2): every pixel's direct is
// albedo x sky = 1 and indirect_diffuse and reflection are 0 (nothing else to bounce from, no
// specular lobe), for every technique
// and every AOV it declares.
TEST_F(AovContract, SkyLitPlaneMatchesAnalyticValues) {
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/sky_plane.json");
  for (const Technique& t : techniques()) {
    std::vector<std::string> res;  // distinct resources (direct's radiance is its direct)
    for (auto& a : contract_aov_names(t, scene.features()))
      if (std::find(res.begin(), res.end(), contract_resource(t, a)) == res.end()) res.push_back(contract_resource(t, a));
    auto imgs = render_mean(gpu(), scene, t.name, res, 3, 1, "low");
    for (auto& a : contract_aov_names(t, scene.features())) {
      // reflection: the plane is Lambertian (no specular lobe), so 0.
      double expect = a == "indirect_diffuse" || a == "reflection" ? 0.0 : 1.0;
      const FloatImage& img = imgs.at(contract_resource(t, a));
      double worst = 0;
      for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
          for (uint32_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(img.at(x, y, c)) - expect));
      std::printf("sky-lit plane %-14s %-16s max |value - %.1f| = %.3g\n", t.name.c_str(), a.c_str(), expect, worst);
      EXPECT_LE(worst, 1e-5) << t.name << " " << a;
    }
  }
}

}  // namespace
}  // namespace gib
