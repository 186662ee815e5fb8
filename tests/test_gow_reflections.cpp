// gow-ragnarok's reflections (gow_ragnarok.md "Reflections"): the cube map's addressing and
// Lagarde's box projection (gow_cubemap.h) on known answers and against the shaders on the
// device, and the graph culling the reflection passes without a glossy material.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/gow_ragnarok/gow_cubemap.h"
#include "renderer/techniques/technique.h"
#include "tests/gow_cubemap_test_shared.h"
#include "tests/gpu_fixture.h"
#include "tests/test_rng.h"

namespace gib {
namespace {

using namespace gow_cubemap_test;

TEST(GowCubemapCpu, FacesRoundTripAndKnownTexels) {
  // Each axis direction lands in the middle of its face: face = 2 axis + negative.
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (uint32_t f = 0; f < 6; ++f) {
    int32_t x, y;
    gow_cube_texel(axes[f], 8, x, y);
    EXPECT_EQ(x, int32_t(f * 8 + 4)) << f;
    EXPECT_EQ(y, 4) << f;
    float s, t;
    EXPECT_EQ(gow_cube_face(axes[f], s, t), f);
  }
  // A corner of +z's face: st = (-1, -1) -> texel (4N, 0); (1, 1) clamps to the last texel.
  int32_t x, y;
  gow_cube_texel({-1, -1, 1.0001f}, 16, x, y);
  EXPECT_EQ(x, 64);
  EXPECT_EQ(y, 0);
  gow_cube_texel({1, 1, 1.0001f}, 16, x, y);
  EXPECT_EQ(x, 79);
  EXPECT_EQ(y, 15);
  // face / st -> direction -> face / st.
  test::Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    const uint32_t f = rng.below(6);
    const float s = rng.uniform(-0.999f, 0.999f), t = rng.uniform(-0.999f, 0.999f);
    float s2, t2;
    ASSERT_EQ(gow_cube_face(gow_cube_dir(f, s, t), s2, t2), f);
    EXPECT_NEAR(s2, s, 1e-6f);
    EXPECT_NEAR(t2, t, 1e-6f);
  }
}

TEST(GowCubemapCpu, BoxProjectionKnownAnswers) {
  const Vec3 lo{-1, -1, -1}, hi{1, 1, 1}, centre{0, 0, 0};
  // From the capture point the look-up is the ray's own direction (no parallax).
  const Vec3 d = normalize({0.3f, -0.5f, 0.8f});
  const Vec3 p = normalize(gow_box_project(centre, d, lo, hi, centre));
  EXPECT_NEAR(p.x, d.x, 1e-6f);
  EXPECT_NEAR(p.y, d.y, 1e-6f);
  EXPECT_NEAR(p.z, d.z, 1e-6f);
  // Off centre: the ray from (0.5, 0, 0) up +y leaves the box at (0.5, 1, 0); the capture at the
  // centre sees that point along (0.5, 1, 0), not along +y.
  EXPECT_FLOAT_EQ(gow_box_exit({0.5f, 0, 0}, {0, 1, 0}, lo, hi), 1.0f);
  const Vec3 q = gow_box_project({0.5f, 0, 0}, {0, 1, 0}, lo, hi, centre);
  EXPECT_FLOAT_EQ(q.x, 0.5f);
  EXPECT_FLOAT_EQ(q.y, 1.0f);
  EXPECT_FLOAT_EQ(q.z, 0.0f);
  // The nearest face wins: from (0.9, 0, 0) along (1, 1, 0)/sqrt2 the x face is 0.1 away.
  EXPECT_NEAR(gow_box_exit({0.9f, 0, 0}, normalize({1, 1, 0}), lo, hi), 0.1f * std::sqrt(2.0f), 1e-6f);
  // Outside the box (the far side behind the origin): 0.
  EXPECT_EQ(gow_box_exit({2, 0, 0}, {1, 0, 0}, lo, hi), 0.0f);
}

class GowCubemapGpu : public test::GpuTest {};

TEST_F(GowCubemapGpu, DeviceMatchesCpuMirror) {
  test::Rng rng(41);
  std::vector<GowCubemapTestQuery> q(4096);
  for (GowCubemapTestQuery& x : q) {
    const Vec3 lo{rng.uniform(-10, -1), rng.uniform(-10, -1), rng.uniform(-10, -1)};
    const Vec3 hi{rng.uniform(1, 10), rng.uniform(1, 10), rng.uniform(1, 10)};
    const Vec3 d = normalize({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    for (int c = 0; c < 3; ++c) {
      x.bmin[c] = lo[c], x.bmax[c] = hi[c], x.d[c] = d[c];
      x.x[c] = rng.uniform(lo[c], hi[c]);
      x.capture[c] = rng.uniform(lo[c], hi[c]);
    }
    x.size = float(4 + rng.below(60));
  }
  static_assert(sizeof(GowCubemapTestQuery) == GOW_CUBEMAP_TEST_QUERY_FLOATS * 4);
  static_assert(sizeof(GowCubemapTestOut) == GOW_CUBEMAP_TEST_OUT_WORDS * 4);
  auto in = gpu().create_buffer(q.size() * sizeof(GowCubemapTestQuery), BufferUsage::storage, "gow_cubemap_test.queries");
  gpu().upload(*in, q.data(), q.size() * sizeof(GowCubemapTestQuery));
  auto out = gpu().create_buffer(q.size() * sizeof(GowCubemapTestOut), BufferUsage::storage, "gow_cubemap_test.out");
  ComputePipelineDesc desc{"gow_cubemap_test.comp",
                           {{GOW_CUBEMAP_TEST_BINDING_QUERIES, DescriptorKind::storage_buffer},
                            {GOW_CUBEMAP_TEST_BINDING_OUT, DescriptorKind::storage_buffer}},
                           sizeof(GowCubemapTestPush)};
  auto pipeline = gpu().compute_pipeline(desc);
  const Bind binds[] = {{GOW_CUBEMAP_TEST_BINDING_QUERIES, in.get()}, {GOW_CUBEMAP_TEST_BINDING_OUT, out.get()}};
  const GowCubemapTestPush push{uint32_t(q.size())};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch((uint32_t(q.size()) + GOW_CUBEMAP_TEST_WORKGROUP_SIZE - 1) / GOW_CUBEMAP_TEST_WORKGROUP_SIZE);
  gpu().submit(std::move(cmd));
  std::vector<GowCubemapTestOut> o(q.size());
  gpu().download(*out, o.data(), o.size() * sizeof(GowCubemapTestOut));

  size_t texel_off = 0;
  float worst = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const GowCubemapTestQuery& x = q[i];
    const Vec3 p{x.x[0], x.x[1], x.x[2]}, d{x.d[0], x.d[1], x.d[2]};
    const Vec3 lo{x.bmin[0], x.bmin[1], x.bmin[2]}, hi{x.bmax[0], x.bmax[1], x.bmax[2]};
    int32_t tx, ty;
    gow_cube_texel(d, uint32_t(x.size), tx, ty);
    // The division of st may round differently on the device (2.5 ulp allowed): a texel
    // boundary can then fall on the other side, by one texel at most.
    if (tx != o[i].texel[0] || ty != o[i].texel[1]) {
      ++texel_off;
      EXPECT_LE(std::abs(tx - o[i].texel[0]) + std::abs(ty - o[i].texel[1]), 1) << "query " << i;
    }
    const Vec3 c = gow_box_project(p, d, lo, hi, {x.capture[0], x.capture[1], x.capture[2]});
    const float e = gow_box_exit(p, d, lo, hi);
    worst = std::fmax(worst, std::fabs(e - o[i].exit) / std::fmax(1.0f, e));
    for (int k = 0; k < 3; ++k) worst = std::fmax(worst, std::fabs(c[k] - o[i].project[k]) / std::fmax(1.0f, std::fabs(c[k])));
  }
  std::printf("gow cube map: %zu queries, %zu texels off by one, worst relative difference %.3g\n", q.size(), texel_off,
              worst);
  EXPECT_LE(texel_off, q.size() / 200);
  EXPECT_LT(worst, 1e-5f);
}

// The reflection passes need a glossy material: without one they are culled with that reason;
// with one they run when `reflection` is asked for, and the cube-map mode reads no screen.
TEST(GowReflectionGraph, GlossyMaterialsRunTheReflectionPasses) {
  const Technique& t = find_technique("gow-ragnarok");
  Settings s = apply_preset(t, "low", Settings{});
  auto find = [](const Plan& pl, const std::string& name) -> const PlannedPass* {
    for (const PlannedPass& p : pl.passes)
      if (p.name == name) return &p;
    return nullptr;
  };
  auto plan = [&](const Scene& scene, const Settings& settings, std::vector<std::string> outputs) {
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, settings));
    CompileOptions o;
    o.features = scene.features();
    o.outputs = std::move(outputs);
    return compile(decls, o);
  };
  const char* kReflectionPasses[] = {"cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"};
  const Scene furnace = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/furnace.json");
  Plan none = plan(furnace, s, {"direct_light"});
  for (const char* name : kReflectionPasses) {
    const PlannedPass* p = find(none, name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_FALSE(p->runs) << name;
    EXPECT_EQ(p->reason, "scene lacks glossy") << name;
  }
  const Scene hall = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/glossy_hall.json");
  Plan rt = plan(hall, s, {"direct_light", "reflection"});
  for (const char* name : kReflectionPasses) EXPECT_TRUE(find(rt, name)->runs) << name;
  // Baseline: the cube map alone still runs capture, trace and resolve.
  Plan cube = plan(hall, apply_options(t, s, {{"reflection_mode", 0}}), {"reflection"});
  for (const char* name : kReflectionPasses) EXPECT_TRUE(find(cube, name)->runs) << name;
  EXPECT_FALSE(find(cube, "direct_lighting")->runs) << "the cube map alone reads no lit screen";
  EXPECT_EQ(contract_aov_names(t, furnace.features()), (std::vector<std::string>{"radiance", "direct", "indirect_diffuse"}));
  EXPECT_EQ(contract_aov_names(t, hall.features()),
            (std::vector<std::string>{"radiance", "direct", "indirect_diffuse", "reflection"}));
}

}  // namespace
}  // namespace gib
