// light_grid pass on lavapipe: every cell of every cascade against the CPU brute force, overflow
// stats, culling without local lights, camera snapping, and the CPU mirror of lg_cell_base.
// Light positions, ranges and camera positions are multiples of 1/4 m and cascade cells are
// powers of two, so every sphere-vs-box test is exact in float on both sides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>

#include "renderer/graph/executor.h"
#include "renderer/techniques/radiance_cache/light_grid/light_grid.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gpu_fixture.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;
using nlohmann::json;

json vec(float x, float y, float z) { return json::array({x, y, z}); }

json base_scene(Vec3 camera) {
  json doc;
  doc["materials"] = {{"grey", {{"albedo", {0.5, 0.5, 0.5}}}}};
  doc["objects"] = json::array(
      {{{"name", "floor"}, {"primitive", {{"type", "quad"}, {"size", {10, 10}}, {"facing", "+y"}}}, {"material", "grey"}}});
  doc["camera"] = {{"position", vec(camera.x, camera.y, camera.z)}, {"target", vec(camera.x, camera.y, camera.z - 1)}};
  doc["lights"] = json::array();
  return doc;
}

float quarter(std::mt19937& rng, float lo, float hi) {  // a multiple of 1/4 in [lo, hi]
  std::uniform_int_distribution<int> d(int(lo * 4), int(hi * 4));
  return float(d(rng)) * 0.25f;
}

// `n` lights: point and spot alternating at random, centred in a cube of half-size `spread`
// around `centre`, ranges in [rmin, rmax].
void add_lights(json& doc, std::mt19937& rng, uint32_t n, Vec3 centre, float spread, float rmin, float rmax) {
  std::uniform_real_distribution<float> u(-1, 1), angle(5, 80);
  for (uint32_t i = 0; i < n; ++i) {
    json l;
    bool spot = rng() & 1;
    l["type"] = spot ? "spot" : "point";
    l["position"] = vec(centre.x + quarter(rng, -spread, spread), centre.y + quarter(rng, -spread, spread),
                        centre.z + quarter(rng, -spread, spread));
    l["intensity"] = vec(1, 1, 1);
    l["range"] = quarter(rng, rmin, rmax);
    if (spot) {
      Vec3 d{u(rng), u(rng), u(rng)};
      if (dot(d, d) < 1e-3f) d = {0, -1, 0};
      l["direction"] = vec(d.x, d.y, d.z);
      float outer = angle(rng);
      l["outer_cone_deg"] = outer;
      l["inner_cone_deg"] = outer * 0.5f;
    }
    doc["lights"].push_back(l);
  }
}

struct GridRun {
  std::vector<uint32_t> words;
  glsl::LightGridStats stats{};
  Plan plan;
  double ms = 0;
};

GridRun run_grid(Gpu& gpu, const Scene& scene, const Settings& settings, LightGridOptions options, uint32_t frames = 1) {
  std::vector<std::unique_ptr<Pass>> passes;
  passes.push_back(make_light_grid_pass(options));
  Executor ex(gpu, scene, settings, std::move(passes), {"light_grid"});
  GridRun r;
  r.plan = ex.plan();
  if (ex.plan().running().empty()) return r;
  for (uint32_t f = 0; f < frames; ++f) {
    FrameResult fr = ex.run_frame();
    for (auto& p : fr.passes)
      if (p.name == "light_grid" && f > 0) r.ms = r.ms > 0 ? std::min(r.ms, p.ms) : p.ms;  // best after frame 0
  }
  std::vector<uint8_t> raw = ex.read_buffer("light_grid");
  r.words.resize(raw.size() / 4);
  std::memcpy(r.words.data(), raw.data(), r.words.size() * 4);
  std::vector<uint8_t> st = ex.read_buffer("light_grid_stats");
  EXPECT_GE(st.size(), sizeof(r.stats));
  std::memcpy(&r.stats, st.data(), sizeof(r.stats));
  return r;
}

std::vector<GpuLight> gpu_lights(const Scene& scene) { return flatten(scene, 0.0f).lights; }

// Compares every cell of every cascade with the CPU brute force; returns the number of
// mismatching cells (reports the first few).
struct Expected {
  uint32_t overflowed = 0, max_lights = 0, nonempty = 0, refs = 0;
};
uint32_t compare_all_cells(const GridRun& r, const std::vector<GpuLight>& lights, const glsl::LightGridParams& p,
                           Vec3 camera, bool cone_cull, Expected& e) {
  uint32_t bad = 0;
  EXPECT_EQ(r.words.size(), light_grid_words(p));
  for (uint32_t c = 0; c < light_grid_cascades(p); ++c)
    for (uint32_t z = 0; z < glsl::kLightGridDim; ++z)
      for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
          const uint32_t local[3] = {x, y, z};
          std::vector<uint32_t> want = lights_for_cell(lights, p, c, local, camera, cone_cull);
          e.max_lights = std::max<uint32_t>(e.max_lights, uint32_t(want.size()));
          e.overflowed += want.size() > glsl::kLightGridMaxLights;
          e.nonempty += !want.empty();
          if (want.size() > glsl::kLightGridMaxLights) want.resize(glsl::kLightGridMaxLights);
          e.refs += uint32_t(want.size());
          uint32_t w = light_grid_cell_word(c, local);
          uint32_t count = r.words[w];
          std::vector<uint32_t> got;
          if (count <= glsl::kLightGridMaxLights) got.assign(r.words.begin() + w + 1, r.words.begin() + w + 1 + count);
          if (count != want.size() || got != want) {
            if (++bad <= 5) {
              std::string g, s;
              for (auto i : got) g += std::to_string(i) + " ";
              for (auto i : want) s += std::to_string(i) + " ";
              ADD_FAILURE() << "cascade " << c << " cell " << x << "," << y << "," << z << ": gpu count " << count
                            << " [" << g << "] cpu [" << s << "]";
            }
          }
        }
  return bad;
}

constexpr Vec3 kCamera{0.25f, 1.5f, -0.75f};

class LightGrid : public GpuTest {
 protected:
  void check(uint32_t n_spread, uint32_t n_cluster, uint32_t seed, bool expect_overflow) {
    std::mt19937 rng(seed);
    json doc = base_scene(kCamera);
    add_lights(doc, rng, n_spread, kCamera, 120.0f, 0.5f, 24.0f);
    add_lights(doc, rng, n_cluster, Vec3{6, 1, -3}, 4.0f, 6.0f, 12.0f);
    Scene scene = parse_scene(doc, "light_grid_test");
    Settings s = defaults_of("radiance-cache");
    glsl::LightGridParams p = make_light_grid_params(s, uint32_t(scene.lights.size()));
    auto lights = gpu_lights(scene);
    for (bool cone : {false, true}) {
      GridRun r = run_grid(gpu(), scene, s, LightGridOptions{cone}, 4);
      ASSERT_FALSE(r.words.empty());
      Expected e;
      EXPECT_EQ(compare_all_cells(r, lights, p, kCamera, cone, e), 0u) << "cone_cull " << cone;
      EXPECT_EQ(r.stats.overflowed_cells, e.overflowed) << "cone_cull " << cone;
      EXPECT_EQ(r.stats.max_lights_in_a_cell, e.max_lights) << "cone_cull " << cone;
      if (expect_overflow) {
        EXPECT_GT(e.overflowed, 0u);
      }
      std::printf("light_grid %zu lights cone_cull=%d: %u non-empty cells, %u ids, %u overflowed, max %u, %.3f ms\n",
                  lights.size(), int(cone), e.nonempty, e.refs, e.overflowed, e.max_lights, r.ms);
      if (cone) conservative(r, lights, p, rng);
    }
  }

  // Cone culling never drops a light that reaches a point: sample points, evaluate each light's
  // support (range, outer cone) and require it in the list of the cell holding the point.
  void conservative(const GridRun& r, const std::vector<GpuLight>& lights, const glsl::LightGridParams& p,
                    std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    std::uniform_int_distribution<size_t> pick(0, lights.size() - 1);
    uint32_t checked = 0, bad = 0;
    for (int k = 0; k < 4000; ++k) {  // points within the range of a random light
      const GpuLight& near = lights[pick(rng)];
      Vec3 x = Vec3{near.position[0], near.position[1], near.position[2]} + Vec3{u(rng), u(rng), u(rng)} * near.range;
      uint32_t w = light_grid_cell_of(p, kCamera, x);
      if (w == kLightGridInvalid || r.words[w] >= glsl::kLightGridMaxLights) continue;
      for (uint32_t i = 0; i < lights.size(); ++i) {
        const GpuLight& l = lights[i];
        Vec3 d = x - Vec3{l.position[0], l.position[1], l.position[2]};
        float dist = length(d);
        if (dist > l.range * 0.999f || dist < 1e-3f) continue;
        if (l.kind == uint32_t(LightKind::spot) &&
            dot(d * (1.0f / dist), Vec3{l.direction[0], l.direction[1], l.direction[2]}) <= l.cos_outer + 1e-4f)
          continue;
        ++checked;
        bool found = false;
        for (uint32_t j = 0; j < r.words[w]; ++j) found |= r.words[w + 1 + j] == i;
        bad += !found;
      }
    }
    EXPECT_EQ(bad, 0u) << "of " << checked << " lit (point, light) pairs";
    EXPECT_GT(checked, 0u);
  }
};

TEST_F(LightGrid, OneLightMatchesCpu) { check(1, 0, 11, false); }
TEST_F(LightGrid, HundredLightsMatchCpu) { check(100, 0, 12, false); }
TEST_F(LightGrid, ThreeHundredLightsOverflowMatchCpu) { check(100, 200, 13, true); }

TEST_F(LightGrid, ConeCullingRemovesSpotCells) {
  std::mt19937 rng(5);
  json doc = base_scene(kCamera);
  add_lights(doc, rng, 60, kCamera, 40.0f, 8.0f, 24.0f);
  Scene scene = parse_scene(doc, "light_grid_cones");
  Settings s = defaults_of("radiance-cache");
  glsl::LightGridParams p = make_light_grid_params(s, uint32_t(scene.lights.size()));
  GridRun sphere = run_grid(gpu(), scene, s, LightGridOptions{false});
  GridRun cone = run_grid(gpu(), scene, s, LightGridOptions{true});
  uint64_t a = 0, b = 0;
  for (uint32_t i = 0; i < light_grid_words(p); i += glsl::kLightGridCellWords) {
    a += sphere.words[i];
    b += cone.words[i];
  }
  std::printf("cell-light pairs: sphere %llu, with cone culling %llu\n", (unsigned long long)a, (unsigned long long)b);
  EXPECT_LT(b, a);
}

TEST_F(LightGrid, SceneWithoutLocalLightsCullsThePass) {
  Scene scene = parse_scene(base_scene(kCamera), "no_lights");
  GridRun r = run_grid(gpu(), scene, defaults_of("radiance-cache"), {});
  ASSERT_EQ(r.plan.passes.size(), 1u);
  EXPECT_FALSE(r.plan.passes[0].runs);
  EXPECT_EQ(r.plan.passes[0].reason, "scene lacks local_lights");
  EXPECT_TRUE(r.words.empty());
  glsl::LightGridParams p = make_light_grid_params(defaults_of("radiance-cache"), 0);
  const uint32_t local[3] = {8, 8, 8};
  EXPECT_TRUE(lights_for_cell({}, p, 0, local, kCamera, true).empty());
}

TEST_F(LightGrid, CameraMotionInsideACellKeepsTheGrid) {
  std::mt19937 rng(7);
  json lights = base_scene(kCamera);
  add_lights(lights, rng, 100, kCamera, 120.0f, 0.5f, 24.0f);
  add_lights(lights, rng, 30, kCamera, 12.0f, 0.5f, 4.0f);
  auto grid_at = [&](Vec3 cam) {
    json doc = lights;
    doc["camera"] = base_scene(cam)["camera"];
    Scene scene = parse_scene(doc, "snap");
    return run_grid(gpu(), scene, defaults_of("radiance-cache"), {}).words;
  };
  // Cascade-0 cells are 2 m; cells of coarser cascades are unions of them.
  auto a = grid_at({0.25f, 1.5f, -0.75f});
  auto b = grid_at({1.75f, 0.25f, -1.75f});  // same 2 m cell: [0,2) x [0,2) x [-2,0)
  auto c = grid_at({2.25f, 1.5f, -0.75f});   // next cascade-0 cell along x: cascade 0 moves
  auto d = grid_at({16.25f, 1.5f, -0.75f});  // next cascade-3 cell: every cascade moves
  ASSERT_EQ(a.size(), b.size());
  auto same = [](const std::vector<uint32_t>& x, const std::vector<uint32_t>& y) {
    for (size_t w = 0; w < x.size(); w += glsl::kLightGridCellWords) {
      if (x[w] != y[w]) return false;
      for (uint32_t j = 0; j < x[w]; ++j)
        if (x[w + 1 + j] != y[w + 1 + j]) return false;
    }
    return true;
  };
  auto cascade = [](const std::vector<uint32_t>& x, uint32_t c) {
    const size_t cells = glsl::kLightGridDim * glsl::kLightGridDim * glsl::kLightGridDim * glsl::kLightGridCellWords;
    return std::vector<uint32_t>(x.begin() + c * cells, x.begin() + (c + 1) * cells);
  };
  EXPECT_TRUE(same(a, b));
  EXPECT_FALSE(same(cascade(a, 0), cascade(c, 0)));
  EXPECT_TRUE(same(cascade(a, 1), cascade(c, 1)));  // 4 m cells: both cameras in [0, 4)
  for (uint32_t k = 0; k < 4; ++k) EXPECT_FALSE(same(cascade(a, k), cascade(d, k))) << "cascade " << k;
}

TEST(LightGridCpu, CellOfPicksTheFinestCascadeContainingThePoint) {
  Settings s = defaults_of("radiance-cache");  // 4 cascades, 32 m: cells 2, 4, 8, 16 m
  glsl::LightGridParams p = make_light_grid_params(s, 1);
  Vec3 cam{0.25f, 1.5f, -0.75f};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-200, 200);
  for (int k = 0; k < 20000; ++k) {
    Vec3 x{u(rng), u(rng), u(rng)};
    uint32_t w = light_grid_cell_of(p, cam, x);
    uint32_t expect = kLightGridInvalid;
    for (uint32_t c = 0; c < 4 && expect == kLightGridInvalid; ++c) {
      float cell = light_grid_cell_size(p, c);
      int32_t base[3];
      light_grid_base_cell(p, c, cam, base);
      uint32_t local[3];
      bool in = true;
      for (int a = 0; a < 3; ++a) {
        double lo = double(base[a]) * cell, rel = (double(x[a]) - lo) / cell;
        in = in && rel >= 0 && rel < 16;
        local[a] = in ? uint32_t(rel) : 0;
      }
      if (in) {
        Vec3 bmin, bmax;
        light_grid_cell_bounds(p, c, local, cam, bmin, bmax);
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(x[a] >= bmin[a] && x[a] < bmax[a]);
        expect = light_grid_cell_word(c, local);
      }
    }
    ASSERT_EQ(w, expect) << x.x << "," << x.y << "," << x.z;
  }
  // Extents: cascade 3 spans 256 m around the camera's 16 m cell [0,16) x [0,16) x [-16,0).
  EXPECT_NE(light_grid_cell_of(p, cam, {127.9f, 0, 0}), kLightGridInvalid);
  EXPECT_EQ(light_grid_cell_of(p, cam, {128.0f, 0, 0}), kLightGridInvalid);
  EXPECT_EQ(light_grid_cell_of(p, cam, {-128.1f, 0, 0}), kLightGridInvalid);
  EXPECT_EQ(light_grid_cell_of(p, cam, cam) % glsl::kLightGridCellWords, 0u);
  EXPECT_LT(light_grid_cell_of(p, cam, cam), 4096u * glsl::kLightGridCellWords);  // cascade 0
}

}  // namespace
}  // namespace gib
