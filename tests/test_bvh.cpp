// BVH build and traversal: CPU BVH against CPU brute force on random triangle soups (zero-area,
// duplicate, huge, tiny, shared-edge triangles), near and 10 km from the origin; degenerate
// builds; watertightness; the tie rule; alpha testing; the CPU material mirror. The GPU part
// (bvh_test.comp against the CPU brute force) is compiled unless GIB_BVH_TEST_NO_GPU is defined.
//
// Near-tie tolerance: two answers that name different triangles are both right when the
// triangles are hit at t within 1e-5 relative of each other (shared edges and vertices,
// duplicates, coplanar overlaps), since float rounding decides which is nearer. The CPU BVH and
// the CPU brute force run the same float operations, so they must agree exactly; the GPU may
// differ by a few ulps (driver division), so GPU comparisons use the tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "renderer/scene/bvh.h"
#include "renderer/scene/material_eval.h"
#include "tests/bvh_test_shared.h"

#ifndef GIB_BVH_TEST_NO_GPU
#include <functional>
#include <memory>
#include <string>

#include "renderer/vk/gpu.h"
#endif

namespace gib {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kSceneBufferCount = 7;  // GIB_SCENE_BINDING_COUNT in scene.glsl

// Small deterministic generator (no dependence on the standard library's distributions).
struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
  uint32_t next() {
    s ^= s >> 12; s ^= s << 25; s ^= s >> 27;
    return uint32_t((s * 0x2545F4914F6CDD1Dull) >> 32);
  }
  float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }  // [0, 1)
  float range(float a, float b) { return a + (b - a) * uniform(); }
  Vec3 in_box(float h) { return {range(-h, h), range(-h, h), range(-h, h)}; }
  Vec3 unit() {
    for (;;) {
      Vec3 v = in_box(1.0f);
      float l = dot(v, v);
      if (l > 1e-4f && l <= 1.0f) return v / std::sqrt(l);
    }
  }
  uint32_t below(uint32_t n) { return next() % n; }
};

struct SoupBuilder {
  FlatScene scene;
  Rng& rng;
  explicit SoupBuilder(Rng& r) : rng(r) {
    scene.instances.push_back(GpuInstance{0, 0, 0, 0});
    GpuMaterial m{};
    m.albedo[0] = m.albedo[1] = m.albedo[2] = 0.8f;
    m.texture_scale = 1.0f;
    m.opacity = 1.0f;
    m.alpha_cutoff = 0.5f;
    scene.materials.push_back(m);
  }
  uint32_t vertex(Vec3 p) {
    scene.vertices.push_back(GpuVertex{p.x, p.y, p.z, rng.uniform(), 0, 1, 0, rng.uniform()});
    return uint32_t(scene.vertices.size() - 1);
  }
  uint32_t tri(uint32_t a, uint32_t b, uint32_t c, uint32_t instance = 0) {
    scene.triangles.push_back(GpuTriangle{a, b, c, instance});
    scene.instances[instance].triangle_count++;
    return uint32_t(scene.triangles.size() - 1);
  }
  uint32_t tri(Vec3 a, Vec3 b, Vec3 c) { return tri(vertex(a), vertex(b), vertex(c)); }
  void random_tri(float size, float box) {
    Vec3 c = rng.in_box(box);
    tri(c + rng.in_box(size), c + rng.in_box(size), c + rng.in_box(size));
  }
};

struct Soup {
  FlatScene scene;
  std::vector<uint32_t> zero_area;  // triangles built to have exactly zero area
  uint32_t grid_first_vertex = 0, grid_n = 0;
};

// About 2,400 triangles in [-10, 10]^3 with every kind of trouble.
Soup make_soup(uint64_t seed) {
  Rng rng(seed);
  SoupBuilder b(rng);
  Soup soup;
  for (int i = 0; i < 1500; ++i) b.random_tri(rng.range(0.1f, 2.0f), 10.0f);
  for (int i = 0; i < 200; ++i) b.random_tri(rng.range(1e-4f, 1e-3f), 10.0f);
  for (int i = 0; i < 20; ++i) b.random_tri(rng.range(50.0f, 200.0f), 10.0f);
  // Long thin slivers (real but tiny area).
  for (int i = 0; i < 50; ++i) {
    Vec3 a = rng.in_box(10.0f), d = rng.unit() * rng.range(1.0f, 10.0f);
    b.tri(a, a + d, a + d * 0.5f + rng.unit() * 1e-4f);
  }
  // Exactly zero area: coincident, two equal, axis-collinear, collinear on a dyadic grid.
  for (int i = 0; i < 40; ++i) {
    Vec3 a = rng.in_box(10.0f);
    soup.zero_area.push_back(b.tri(a, a, a));
    Vec3 c = rng.in_box(10.0f);
    uint32_t va = b.vertex(a);
    soup.zero_area.push_back(b.tri(va, va, b.vertex(c)));
    Vec3 e = a;
    e.x += rng.range(0.5f, 3.0f);
    Vec3 m = a;
    m.x = a.x + (e.x - a.x) * 0.25f;
    soup.zero_area.push_back(b.tri(a, e, m));
    // Collinear with exact coordinates: multiples of 1/64 along a direction of small integers.
    Vec3 g{float(int(rng.range(-600, 600))) / 64.0f, float(int(rng.range(-600, 600))) / 64.0f,
           float(int(rng.range(-600, 600))) / 64.0f};
    Vec3 dir{float(int(rng.range(-8, 8))) / 16.0f, float(int(rng.range(-8, 8))) / 16.0f, 0.5f};
    soup.zero_area.push_back(b.tri(g, g + dir * 4.0f, g + dir * 1.5f));
  }
  // Duplicates: same vertices again (shared indices and copied vertices), and a reversed one.
  const uint32_t before = uint32_t(b.scene.triangles.size());
  for (int i = 0; i < 100; ++i) {
    const uint32_t src = rng.below(before);
    const GpuTriangle t = b.scene.triangles[src];
    if (std::find(soup.zero_area.begin(), soup.zero_area.end(), src) != soup.zero_area.end()) {
      soup.zero_area.push_back(uint32_t(b.scene.triangles.size()));
    }
    if (i % 2 == 0) {
      b.tri(t.i0, t.i1, t.i2);
    } else {
      const GpuVertex v0 = b.scene.vertices[t.i0], v1 = b.scene.vertices[t.i1],
                      v2 = b.scene.vertices[t.i2];
      b.tri({v0.px, v0.py, v0.pz}, {v1.px, v1.py, v1.pz}, {v2.px, v2.py, v2.pz});
    }
  }
  // A shared-vertex height field: rays aimed at its vertices and edges must not leak.
  const uint32_t n = 16;
  soup.grid_first_vertex = uint32_t(b.scene.vertices.size());
  soup.grid_n = n;
  for (uint32_t z = 0; z <= n; ++z) {
    for (uint32_t x = 0; x <= n; ++x) {
      b.vertex({-8.0f + x, -9.0f + rng.range(-0.5f, 0.5f), -8.0f + z});
    }
  }
  for (uint32_t z = 0; z < n; ++z) {
    for (uint32_t x = 0; x < n; ++x) {
      uint32_t v00 = soup.grid_first_vertex + z * (n + 1) + x, v10 = v00 + 1;
      uint32_t v01 = v00 + n + 1, v11 = v01 + 1;
      if ((x + z) % 2) {
        b.tri(v00, v10, v11);
        b.tri(v00, v11, v01);
      } else {
        b.tri(v00, v10, v01);
        b.tri(v10, v11, v01);
      }
    }
  }
  soup.scene = std::move(b.scene);
  return soup;
}

struct TestRay {
  Ray ray;
  float tmin, tmax;
};

Vec3 pos(const FlatScene& s, uint32_t v) {
  return {s.vertices[v].px, s.vertices[v].py, s.vertices[v].pz};
}

std::vector<TestRay> make_rays(const Soup& soup, uint64_t seed, size_t count) {
  Rng rng(seed);
  const FlatScene& s = soup.scene;
  std::vector<TestRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const uint32_t kind = rng.below(10);
    TestRay r{{rng.in_box(15.0f), {0, 1, 0}}, 0.0f, kInf};
    const GpuTriangle& t = s.triangles[rng.below(uint32_t(s.triangles.size()))];
    if (kind < 4) {  // at a random point of a random triangle
      float a = rng.uniform(), c = rng.uniform();
      if (a + c > 1) { a = 1 - a; c = 1 - c; }
      Vec3 target = pos(s, t.i0) * (1 - a - c) + pos(s, t.i1) * a + pos(s, t.i2) * c;
      r.ray.dir = target - r.ray.origin;
    } else if (kind < 6) {  // anywhere
      r.ray.dir = rng.unit() * rng.range(0.01f, 100.0f);
    } else if (kind < 7) {  // along an axis through a vertex (zero direction components)
      const int axis = int(rng.below(3));
      Vec3 d{0, 0, 0};
      d[axis] = rng.uniform() < 0.5f ? -1.0f : 1.0f;
      const Vec3 v = pos(s, rng.uniform() < 0.5f ? t.i0 : t.i1);
      r.ray = {v - d * 20.0f, d};
    } else if (kind < 9) {  // at a vertex or an edge midpoint of the height field
      const uint32_t n = soup.grid_n;
      const uint32_t x = rng.below(n), z = rng.below(n);
      const uint32_t v00 = soup.grid_first_vertex + z * (n + 1) + x;
      const uint32_t other = rng.uniform() < 0.5f ? v00 + 1 : v00 + n + 1 + rng.below(2);
      Vec3 target = rng.uniform() < 0.5f ? pos(s, v00) : (pos(s, v00) + pos(s, other)) * 0.5f;
      r.ray.origin = target + Vec3{rng.range(-3, 3), rng.range(1, 20), rng.range(-3, 3)};
      r.ray.dir = target - r.ray.origin;
    } else {  // bounded interval
      r.ray.dir = rng.unit();
      r.tmin = rng.range(0.0f, 5.0f);
      r.tmax = r.tmin + rng.range(0.0f, 20.0f);
    }
    rays.push_back(r);
  }
  return rays;
}

FlatScene translated(const FlatScene& s, Vec3 offset) {
  FlatScene out = s;
  for (GpuVertex& v : out.vertices) {
    v.px += offset.x;
    v.py += offset.y;
    v.pz += offset.z;
  }
  return out;
}

bool same_hit(const Hit& a, const Hit& b) {
  if (a.hit != b.hit) return false;
  if (!a.hit) return true;
  return a.triangle == b.triangle && a.t == b.t && a.u == b.u && a.v == b.v;
}

bool near_tie(const Hit& a, const Hit& b) {
  return a.hit && b.hit && std::fabs(a.t - b.t) <= 1e-5f * std::max(1.0f, std::fabs(a.t));
}

void check_structure(const Bvh& bvh, const FlatScene& scene) {
  // Every valid triangle exactly once; children inside parents; leaves small.
  std::vector<int> seen(scene.triangles.size(), 0);
  for (uint32_t id : bvh.tri_index) seen[id]++;
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    ASSERT_EQ(seen[i], triangle_is_degenerate(scene, i) ? 0 : 1) << "triangle " << i;
  }
  for (const GpuBvhNode& n : bvh.nodes) {
    if (n.count > 0) {
      EXPECT_LE(n.count, 8u);
      for (uint32_t s = n.left_or_first; s < n.left_or_first + n.count; ++s) {
        const GpuTriangle& t = scene.triangles[bvh.tri_index[s]];
        for (uint32_t vi : {t.i0, t.i1, t.i2}) {
          const Vec3 p = pos(scene, vi);
          for (int k = 0; k < 3; ++k) {
            EXPECT_LT(n.bmin[k], p[k]);
            EXPECT_GT(n.bmax[k], p[k]);
          }
        }
      }
    } else if (n.left_or_first != 0) {
      ASSERT_LT(n.left_or_first + 1, bvh.nodes.size());
      for (uint32_t c : {n.left_or_first, n.left_or_first + 1}) {
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(n.bmin[k], bvh.nodes[c].bmin[k]);
          EXPECT_GE(n.bmax[k], bvh.nodes[c].bmax[k]);
        }
      }
    }
  }
  EXPECT_LT(bvh.stats.max_depth, kBvhMaxDepth);
  EXPECT_TRUE(std::isfinite(bvh.stats.sah_cost));
}

struct Comparison {
  size_t rays = 0, hits = 0, exact = 0, near_ties = 0, hard = 0, degenerate_hits = 0,
         occlusion_mismatch = 0;
};

Comparison compare_cpu(const Soup& soup, const FlatScene& scene, const std::vector<TestRay>& rays,
                       const Bvh& bvh) {
  Comparison c;
  std::vector<char> degenerate(scene.triangles.size());
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) degenerate[i] = triangle_is_degenerate(scene, i);
  for (uint32_t z : soup.zero_area) EXPECT_TRUE(degenerate[z]) << "zero-area triangle " << z;
  for (const TestRay& r : rays) {
    const Hit bf = intersect_brute_force(scene, r.ray, r.tmin, r.tmax);
    const Hit bv = intersect_bvh(bvh, scene, r.ray, r.tmin, r.tmax);
    const bool occ = occluded_bvh(bvh, scene, r.ray, r.tmin, r.tmax);
    c.rays++;
    c.hits += bf.hit;
    if (bf.hit && degenerate[bf.triangle]) c.degenerate_hits++;
    if (bv.hit && degenerate[bv.triangle]) c.degenerate_hits++;
    if (occ != bf.hit) c.occlusion_mismatch++;
    if (same_hit(bf, bv)) c.exact++;
    else if (near_tie(bf, bv)) c.near_ties++;
    else c.hard++;
  }
  return c;
}

void print(const char* what, const Comparison& c) {
  std::printf("[bvh] %s: %zu rays, %zu hits, %zu exact, %zu near-ties, %zu hard, "
              "%zu occlusion mismatches\n",
              what, c.rays, c.hits, c.exact, c.near_ties, c.hard, c.occlusion_mismatch);
}

TEST(Bvh, CpuBvhMatchesBruteForce) {
  const Soup soup = make_soup(1);
  const Bvh bvh = build_bvh(soup.scene);
  check_structure(bvh, soup.scene);
  std::printf("[bvh] %u triangles (%u skipped), %u nodes, %u leaves, depth %u, SAH %.2f, %.2f ms\n",
              bvh.stats.triangles, bvh.stats.skipped_triangles, bvh.stats.nodes,
              bvh.stats.leaves, bvh.stats.max_depth, bvh.stats.sah_cost, bvh.stats.build_ms);
  EXPECT_EQ(bvh.stats.skipped_triangles, soup.zero_area.size());
  const std::vector<TestRay> rays = make_rays(soup, 2, 12000);
  const Comparison c = compare_cpu(soup, soup.scene, rays, bvh);
  print("centred", c);
  EXPECT_EQ(c.exact, c.rays);  // same float operations: no tolerance needed
  EXPECT_EQ(c.degenerate_hits, 0u);
  EXPECT_EQ(c.occlusion_mismatch, 0u);
  EXPECT_GT(c.hits, c.rays / 2);  // the rays do hit things
}

TEST(Bvh, CpuBvhMatchesBruteForceTenKilometresOut) {
  const Soup soup = make_soup(3);
  const Vec3 offset{10000.0f, 2000.0f, -3000.0f};
  const FlatScene far = translated(soup.scene, offset);
  std::vector<TestRay> rays = make_rays(soup, 4, 12000);
  std::vector<TestRay> far_rays = rays;
  for (TestRay& r : far_rays) r.ray.origin = r.ray.origin + offset;
  const Bvh bvh = build_bvh(far);
  check_structure(bvh, far);
  std::printf("[bvh] 10 km: %u triangles (%u skipped: tiny ones collapse)\n", bvh.stats.triangles,
              bvh.stats.skipped_triangles);
  const Comparison c = compare_cpu(soup, far, far_rays, bvh);
  print("10 km", c);
  EXPECT_EQ(c.exact, c.rays);
  EXPECT_EQ(c.degenerate_hits, 0u);
  EXPECT_EQ(c.occlusion_mismatch, 0u);

  // Against the centred scene: float spacing at 10 km is 1 mm, so tiny triangles and rays
  // aimed at edges move; most answers must still be the same triangle at about the same t.
  const Bvh centred = build_bvh(soup.scene);
  size_t same = 0, t_close = 0, both = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit a = intersect_bvh(centred, soup.scene, rays[i].ray, rays[i].tmin, rays[i].tmax);
    const Hit b = intersect_bvh(bvh, far, far_rays[i].ray, far_rays[i].tmin, far_rays[i].tmax);
    if (a.hit == b.hit && (!a.hit || a.triangle == b.triangle)) same++;
    if (a.hit && b.hit) {
      both++;
      if (std::fabs(a.t - b.t) <= 1e-2f * std::max(1.0f, a.t)) t_close++;
    }
  }
  std::printf("[bvh] 10 km vs centred: %zu/%zu same answer, %zu/%zu hit t within 1%%\n", same,
              rays.size(), t_close, both);
  // Measured: 96.2 % and 98.7 %.
  EXPECT_GE(same, rays.size() * 93 / 100);
  EXPECT_GE(t_close, both * 97 / 100);
}

TEST(Bvh, DegenerateInputsTerminate) {
  Rng rng(5);
  {  // 1,000 copies of one triangle: all centroids equal
    SoupBuilder b(rng);
    const uint32_t v0 = b.vertex({0, 0, 0}), v1 = b.vertex({1, 0, 0}), v2 = b.vertex({0, 1, 0});
    for (int i = 0; i < 1000; ++i) b.tri(v0, v1, v2);
    const Bvh bvh = build_bvh(b.scene);
    check_structure(bvh, b.scene);
    EXPECT_EQ(bvh.stats.triangles, 1000u);
    EXPECT_LT(bvh.stats.max_depth, 12u);
    const Ray ray{{0.25f, 0.25f, 5.0f}, {0, 0, -1}};
    const Hit h = intersect_bvh(bvh, b.scene, ray, 0.0f, kInf);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.triangle, 0u);  // tie: lowest id
    EXPECT_EQ(h.t, 5.0f);
    EXPECT_EQ(h.u, 0.25f);
    EXPECT_EQ(h.v, 0.25f);
  }
  {  // only zero-area triangles: empty BVH, nothing is ever hit
    SoupBuilder b(rng);
    for (int i = 0; i < 500; ++i) {
      const Vec3 a = rng.in_box(1.0f);
      if (i % 2) b.tri(a, a, a);
      else b.tri(a, a + Vec3{1, 0, 0}, a + Vec3{3, 0, 0});
    }
    const Bvh bvh = build_bvh(b.scene);
    EXPECT_EQ(bvh.stats.triangles, 0u);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].count, 0u);
    EXPECT_EQ(bvh.nodes[0].left_or_first, 0u);
    for (int i = 0; i < 200; ++i) {
      const Ray ray{rng.in_box(2.0f), rng.unit()};
      EXPECT_FALSE(intersect_bvh(bvh, b.scene, ray, 0.0f, kInf).hit);
      EXPECT_FALSE(intersect_brute_force(b.scene, ray, 0.0f, kInf).hit);
      EXPECT_FALSE(occluded_bvh(bvh, b.scene, ray, 0.0f, kInf));
    }
  }
  {  // no triangles; NaN vertices
    FlatScene empty;
    const Bvh bvh = build_bvh(empty);
    EXPECT_FALSE(intersect_bvh(bvh, empty, Ray{{0, 0, 0}, {0, 0, 1}}, 0.0f, kInf).hit);
    SoupBuilder b(rng);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    b.tri({nan, 0, 0}, {1, 0, 0}, {0, 1, 0});
    b.tri({0, 0, 0}, {kInf, 0, 0}, {0, 1, 0});
    EXPECT_EQ(build_bvh(b.scene).stats.triangles, 0u);
  }
  {  // a million-to-one spread of sizes along a line: depth stays bounded
    SoupBuilder b(rng);
    float x = 1e-3f;
    for (int i = 0; i < 4000; ++i, x *= 1.004f) b.tri({x, 0, 0}, {x * 1.001f, 1e-3f, 0}, {x, 0, 1e-3f});
    const Bvh bvh = build_bvh(b.scene);
    check_structure(bvh, b.scene);
  }
}

TEST(Bvh, RayParametersAndTies) {
  Rng rng(6);
  SoupBuilder b(rng);
  // Two coincident squares (ids 0-1 and 2-3), then one at z = -1.
  for (float z : {0.0f, 0.0f, -1.0f}) {
    const uint32_t a = b.vertex({-1, -1, z}), c = b.vertex({1, -1, z}), d = b.vertex({1, 1, z}),
                   e = b.vertex({-1, 1, z});
    b.tri(a, c, d);
    b.tri(a, d, e);
  }
  const Bvh bvh = build_bvh(b.scene);
  const Ray down{{0.3f, 0.2f, 2.0f}, {0, 0, -1}};
  Hit h = intersect_bvh(bvh, b.scene, down, 0.0f, kInf);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.triangle, 0u);
  EXPECT_EQ(h.t, 2.0f);
  EXPECT_TRUE(intersect_bvh(bvh, b.scene, down, 0.0f, 2.0f).hit);   // tmax inclusive
  EXPECT_FALSE(intersect_bvh(bvh, b.scene, down, 0.0f, 1.99f).hit);
  h = intersect_bvh(bvh, b.scene, down, 2.5f, kInf);                 // tmin skips the first
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.triangle, 4u);
  EXPECT_EQ(h.t, 3.0f);
  // On the diagonal shared by triangles 0 and 1: the lower id, hit exactly once.
  h = intersect_bvh(bvh, b.scene, Ray{{0.5f, 0.5f, 2.0f}, {0, 0, -1}}, 0.0f, kInf);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.triangle, 0u);
  // Barycentrics: p = p0 + u (p1 - p0) + v (p2 - p0).
  h = intersect_bvh(bvh, b.scene, Ray{{0.5f, -0.5f, 2.0f}, {0, 0, -1}}, 0.0f, kInf);
  ASSERT_TRUE(h.hit);
  EXPECT_FLOAT_EQ(h.u, 0.5f);
  EXPECT_FLOAT_EQ(h.v, 0.25f);
  // Unscaled direction: t in units of dir. Backfaces hit too.
  h = intersect_bvh(bvh, b.scene, Ray{{0.3f, 0.2f, -3.0f}, {0, 0, 4}}, 0.0f, kInf);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.triangle, 4u);
  EXPECT_EQ(h.t, 0.5f);
  // Zero and non-finite rays miss.
  EXPECT_FALSE(intersect_bvh(bvh, b.scene, Ray{{0, 0, 2}, {0, 0, 0}}, 0.0f, kInf).hit);
  EXPECT_FALSE(intersect_bvh(bvh, b.scene, Ray{{0, 0, 2}, {0, 0, -kInf}}, 0.0f, kInf).hit);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(intersect_bvh(bvh, b.scene, Ray{{nan, 0, 2}, {0, 0, -1}}, 0.0f, kInf).hit);
}

// A closed, shared-vertex mesh (a subdivided, jittered cube): every ray from inside must hit,
// including rays aimed exactly at its vertices and edge midpoints.
TEST(Bvh, ClosedMeshDoesNotLeak) {
  Rng rng(7);
  SoupBuilder b(rng);
  const int n = 12;
  // Shared vertices on the cube surface, indexed by integer lattice coordinates.
  auto key = [&](int x, int y, int z) { return (x * (n + 1) + y) * (n + 1) + z; };
  std::vector<int32_t> index((n + 1) * (n + 1) * (n + 1), -1);
  auto vert = [&](int x, int y, int z) {
    int& i = index[key(x, y, z)];
    if (i < 0) {
      Vec3 p{float(x) / n * 2 - 1, float(y) / n * 2 - 1, float(z) / n * 2 - 1};
      p = p * (1.0f + 0.05f * rng.uniform()) + Vec3{0.37f, -0.21f, 0.13f};
      i = int32_t(b.vertex(p));
    }
    return uint32_t(i);
  };
  std::vector<uint32_t> surface;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side <= n; side += n) {
      for (int a = 0; a < n; ++a) {
        for (int c = 0; c < n; ++c) {
          auto at = [&](int i, int j) {
            int p[3];
            p[axis] = side; p[(axis + 1) % 3] = i; p[(axis + 2) % 3] = j;
            return vert(p[0], p[1], p[2]);
          };
          const uint32_t v00 = at(a, c), v10 = at(a + 1, c), v01 = at(a, c + 1), v11 = at(a + 1, c + 1);
          b.tri(v00, v10, v11);
          b.tri(v00, v11, v01);
          surface.push_back(v00);
        }
      }
    }
  }
  const Bvh bvh = build_bvh(b.scene);
  size_t misses = 0, rays = 0;
  for (int i = 0; i < 6000; ++i) {
    const Vec3 o = rng.in_box(0.5f) + Vec3{0.37f, -0.21f, 0.13f};
    Vec3 target;
    const uint32_t v = surface[rng.below(uint32_t(surface.size()))];
    if (i % 3 == 0) target = pos(b.scene, v);
    else if (i % 3 == 1) target = (pos(b.scene, v) + pos(b.scene, v + 1)) * 0.5f;
    else target = o + rng.unit();
    const Ray ray{o, target - o};
    rays++;
    misses += !intersect_bvh(bvh, b.scene, ray, 0.0f, kInf).hit;
    misses += !intersect_brute_force(b.scene, ray, 0.0f, kInf).hit;
    misses += !occluded_bvh(bvh, b.scene, ray, 0.0f, kInf);
  }
  std::printf("[bvh] closed mesh: %zu rays from inside, %zu leaks\n", rays, misses);
  EXPECT_EQ(misses, 0u);
}

TEST(Bvh, AlphaTestMatchesBruteForce) {
  Soup soup = make_soup(8);
  FlatScene& s = soup.scene;
  // Four materials: opaque, leaf mask, checker mask, 40 % opacity; triangles spread over them.
  s.materials.resize(4, s.materials[0]);
  s.materials[1].alpha = uint32_t(AlphaKind::leaf_mask);
  s.materials[2].alpha = uint32_t(AlphaKind::checker_mask);
  s.materials[2].texture_scale = 4.0f;
  s.materials[3].alpha = uint32_t(AlphaKind::opacity);
  s.materials[3].opacity = 0.4f;
  s.instances.assign(4, GpuInstance{});
  for (uint32_t i = 0; i < 4; ++i) s.instances[i].material = i;
  for (uint32_t i = 0; i < s.triangles.size(); ++i) s.triangles[i].instance = i % 4;
  const Bvh bvh = build_bvh(s);
  const std::vector<TestRay> rays = make_rays(soup, 9, 6000);
  struct Ctx { const FlatScene* s; uint32_t seed; size_t calls; size_t rejected; } ctx{&s, 0, 0, 0};
  AlphaTest alpha{[](const void* u, uint32_t tri, float bu, float bv) {
                    auto* c = const_cast<Ctx*>(static_cast<const Ctx*>(u));
                    c->calls++;
                    const bool ok = alpha_accept_default(*c->s, tri, bu, bv, c->seed);
                    c->rejected += !ok;
                    return ok;
                  },
                  &ctx};
  size_t mismatches = 0, hits = 0, opaque_hits = 0;
  for (uint32_t i = 0; i < rays.size(); ++i) {
    const TestRay& r = rays[i];
    ctx.seed = i;
    const Hit bf = intersect_brute_force(s, r.ray, r.tmin, r.tmax, alpha);
    const Hit bv = intersect_bvh(bvh, s, r.ray, r.tmin, r.tmax, alpha);
    const bool occ = occluded_bvh(bvh, s, r.ray, r.tmin, r.tmax, alpha);
    mismatches += !same_hit(bf, bv) || occ != bf.hit;
    hits += bf.hit;
    opaque_hits += intersect_bvh(bvh, s, r.ray, r.tmin, r.tmax).hit;
    if (bf.hit) {
      EXPECT_TRUE(alpha_accept_default(s, bf.triangle, bf.u, bf.v, i));
    }
  }
  std::printf("[bvh] alpha: %zu rays, %zu hits (%zu without alpha), %zu candidates rejected, "
              "%zu mismatches\n", rays.size(), hits, opaque_hits, ctx.rejected, mismatches);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(ctx.rejected, rays.size() / 20);  // alpha really removed hits
  EXPECT_LT(hits, opaque_hits);
}

TEST(Bvh, MaterialMirror) {
  GpuMaterial m{};
  m.albedo[0] = 1; m.albedo[1] = 0.5f; m.albedo[2] = 0.25f;
  m.albedo2[0] = 0; m.albedo2[1] = 0.1f; m.albedo2[2] = 0.2f;
  m.texture_scale = 4.0f;
  m.texture = uint32_t(TextureKind::checker);
  EXPECT_EQ(material_albedo(m, {0.1f, 0.1f}).x, 1.0f);   // cell (0, 0)
  EXPECT_EQ(material_albedo(m, {0.3f, 0.1f}).x, 0.0f);   // cell (1, 0)
  EXPECT_EQ(material_albedo(m, {0.3f, 0.3f}).x, 1.0f);   // cell (1, 1)
  EXPECT_EQ(material_albedo(m, {-0.1f, 0.1f}).x, 0.0f);  // cell (-1, 0)
  m.texture = uint32_t(TextureKind::value_noise);
  float lo = 1, hi = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec2 uv{float(i % 37) * 0.173f, float(i / 37) * 0.091f};
    const float n = material_value_noise(uv);
    ASSERT_GE(n, 0.0f);
    ASSERT_LT(n, 1.0f);
    lo = std::min(lo, n);
    hi = std::max(hi, n);
    const Vec3 c = material_albedo(m, {uv.x / 4, uv.y / 4});
    EXPECT_NEAR(c.x, 1.0f - n, 1e-6f);  // albedo -> albedo2 by the noise
    // Continuous: a tiny step changes the value a little.
    EXPECT_NEAR(material_value_noise({uv.x + 1e-4f, uv.y}), n, 1e-3f);
  }
  EXPECT_LT(lo, 0.2f);
  EXPECT_GT(hi, 0.8f);
  // Lattice points take the hash value of their cell.
  EXPECT_EQ(material_value_noise({3, -2}), material_hash01(material_hash2(3u, uint32_t(-2))));
  m.alpha = uint32_t(AlphaKind::leaf_mask);
  EXPECT_EQ(material_alpha(m, {0.5f, 0.5f}, 0), 1.0f);
  EXPECT_EQ(material_alpha(m, {0.5f, 0.95f}, 0), 1.0f);  // long axis along v
  EXPECT_EQ(material_alpha(m, {0.9f, 0.5f}, 0), 0.0f);   // narrow along u
  EXPECT_EQ(material_alpha(m, {0.02f, 0.02f}, 0), 0.0f);
  m.alpha = uint32_t(AlphaKind::checker_mask);
  EXPECT_EQ(material_alpha(m, {0.1f, 0.1f}, 0), 1.0f);
  EXPECT_EQ(material_alpha(m, {0.3f, 0.1f}, 0), 0.0f);
  m.alpha = uint32_t(AlphaKind::opacity);
  m.opacity = 0.3f;
  EXPECT_EQ(material_alpha(m, {0.3f, 0.1f}, 0), 0.3f);
  EXPECT_EQ(material_hash(0u), 0u);
  EXPECT_NE(material_hash(1u), material_hash(2u));
}


#ifndef GIB_BVH_TEST_NO_GPU
// ---- GPU traversal (bvh_test.comp on lavapipe or a real GPU) against the CPU brute force.

struct GpuRun {
  std::vector<bvh_test::BvhTestHit> hits;
  std::vector<std::string> validation;
};

GpuRun run_gpu(Gpu& gpu, const FlatScene& scene, const Bvh& bvh,
               const std::vector<TestRay>& rays, uint32_t flags) {
  using namespace bvh_test;
  std::vector<std::shared_ptr<Buffer>> keep;
  auto buffer = [&](const void* data, uint64_t bytes, const char* name) {
    // Vulkan has no empty buffers: an empty array still gets one zeroed element's worth.
    auto b = gpu.create_buffer(std::max<uint64_t>(bytes, 64), BufferUsage::storage, name);
    std::vector<uint8_t> zero(64, 0);
    gpu.upload(*b, bytes ? data : zero.data(), bytes ? bytes : 64);
    keep.push_back(b);
    return b;
  };
  auto bytes_of = [](const auto& v) { return uint64_t(v.size() * sizeof(v[0])); };
  std::vector<BvhTestRay> gpu_rays(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    const TestRay& r = rays[i];
    gpu_rays[i] = BvhTestRay{r.ray.origin.x, r.ray.origin.y, r.ray.origin.z, r.tmin,
                             r.ray.dir.x, r.ray.dir.y, r.ray.dir.z, r.tmax};
  }
  const Buffer* scene_buffers[kSceneBufferCount] = {
      buffer(scene.vertices.data(), bytes_of(scene.vertices), "bvh_test.vertices").get(),
      buffer(scene.triangles.data(), bytes_of(scene.triangles), "bvh_test.triangles").get(),
      buffer(scene.instances.data(), bytes_of(scene.instances), "bvh_test.instances").get(),
      buffer(scene.materials.data(), bytes_of(scene.materials), "bvh_test.materials").get(),
      buffer(bvh.nodes.data(), bytes_of(bvh.nodes), "bvh_test.bvh_nodes").get(),
      buffer(bvh.tri_index.data(), bytes_of(bvh.tri_index), "bvh_test.bvh_tri_index").get(),
      buffer(scene.lights.data(), bytes_of(scene.lights), "bvh_test.lights").get(),
  };
  const auto ray_buf = buffer(gpu_rays.data(), bytes_of(gpu_rays), "bvh_test.rays");
  const auto hit_buf = gpu.create_buffer(rays.size() * sizeof(BvhTestHit), BufferUsage::storage,
                                         "bvh_test.hits");
  ComputePipelineDesc desc;
  desc.shader = "bvh_test.comp";
  desc.push_constant_bytes = sizeof(BvhTestPush);
  std::vector<Bind> binds;
  for (uint32_t i = 0; i < kSceneBufferCount; ++i) {
    desc.bindings.push_back({BVH_TEST_BINDING_SCENE + i, DescriptorKind::storage_buffer});
    binds.push_back({BVH_TEST_BINDING_SCENE + i, scene_buffers[i]});
  }
  desc.bindings.push_back({BVH_TEST_BINDING_RAYS, DescriptorKind::storage_buffer});
  desc.bindings.push_back({BVH_TEST_BINDING_HITS, DescriptorKind::storage_buffer});
  binds.push_back({BVH_TEST_BINDING_RAYS, ray_buf.get()});
  binds.push_back({BVH_TEST_BINDING_HITS, hit_buf.get()});
  const auto pipeline = gpu.compute_pipeline(desc);
  const BvhTestPush push{uint32_t(rays.size()), flags};
  auto cmd = gpu.begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch((uint32_t(rays.size()) + BVH_TEST_WORKGROUP_SIZE - 1) / BVH_TEST_WORKGROUP_SIZE);
  gpu.submit(std::move(cmd));
  GpuRun run;
  run.hits.resize(rays.size());
  gpu.download(*hit_buf, run.hits.data(), bytes_of(run.hits));
  run.validation = gpu.validation_messages();
  return run;
}

struct GpuComparison {
  size_t rays = 0, hits = 0, equal = 0, same_triangle = 0, near_ties = 0, edge_grazes = 0,
         hard = 0, any_mismatch = 0;
  bool reported = false;
  float max_t_rel = 0, max_uv = 0;
};

// Tolerances (see the top of the file): t 1e-5 relative, barycentrics 1e-4 on the same
// triangle; a different triangle at t within 1e-5; a hit only one side sees within 1e-5 (in
// barycentrics) of the hit triangle's edge, or within 1e-5 of tmin / tmax.
GpuComparison compare_gpu(const FlatScene& scene, const std::vector<TestRay>& rays,
                          const GpuRun& run, AlphaTest alpha,
                          const std::function<void(uint32_t)>& set_seed) {
  GpuComparison c;
  auto rel = [](float a, float b) { return std::fabs(a - b) / std::max(1.0f, std::fabs(b)); };
  auto grazes = [&](const Hit& h, const TestRay& r) {
    const float w = 1.0f - h.u - h.v;
    return std::min({h.u, h.v, w}) <= 1e-5f || rel(h.t, r.tmin) <= 1e-5f ||
           (std::isfinite(r.tmax) && rel(h.t, r.tmax) <= 1e-5f);
  };
  for (uint32_t i = 0; i < rays.size(); ++i) {
    set_seed(i);
    const TestRay& r = rays[i];
    const Hit cpu = intersect_brute_force(scene, r.ray, r.tmin, r.tmax, alpha);
    const bvh_test::BvhTestHit& g = run.hits[i];
    const Hit gpu{g.t, g.triangle, g.u, g.v, g.hit != 0};
    c.rays++;
    c.hits += cpu.hit;
    c.any_mismatch += (g.any_hit != 0) != gpu.hit;
    if (cpu.hit && gpu.hit && cpu.triangle == gpu.triangle) {
      c.same_triangle++;
      c.equal += same_hit(cpu, gpu);
      const float dt = rel(gpu.t, cpu.t);
      const float duv = std::max(std::fabs(gpu.u - cpu.u), std::fabs(gpu.v - cpu.v));
      c.max_t_rel = std::max(c.max_t_rel, dt);
      c.max_uv = std::max(c.max_uv, duv);
      if (dt > 1e-5f || duv > 1e-4f) c.hard++;
    } else if (!cpu.hit && !gpu.hit) {
      c.equal++;
    } else if (cpu.hit && gpu.hit) {
      // Another triangle about as near: fine if the CPU agrees that it is hit, or if both
      // answers lie on an edge (the ray passes through a shared edge or vertex).
      const Hit check = intersect_triangle(scene, gpu.triangle, r.ray);
      if (rel(gpu.t, cpu.t) > 1e-5f) c.hard++;
      else if (check.hit && rel(check.t, cpu.t) <= 1e-5f) c.near_ties++;
      else if (grazes(cpu, r) && grazes(gpu, r)) c.edge_grazes++;
      else c.hard++;
    } else {
      const Hit& seen = cpu.hit ? cpu : gpu;
      if (grazes(seen, r)) c.edge_grazes++;
      else c.hard++;
    }
    if (c.hard && !c.reported) {  // the first disagreement, for the failure message
      c.reported = true;
      std::printf("[bvh gpu] hard mismatch: ray %u o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) [%g %g] cpu %d %u t=%.9g u=%.9g v=%.9g  gpu %d %u t=%.9g u=%.9g v=%.9g any %u\n",
        i, r.ray.origin.x, r.ray.origin.y, r.ray.origin.z, r.ray.dir.x, r.ray.dir.y, r.ray.dir.z, r.tmin, r.tmax,
        cpu.hit, cpu.triangle, cpu.t, cpu.u, cpu.v, gpu.hit, gpu.triangle, gpu.t, gpu.u, gpu.v, g.any_hit);
    }
  }
  return c;
}

void print(const char* what, const GpuComparison& c) {
  std::printf("[bvh gpu] %s: %zu rays, %zu hits, %zu equal, %zu same triangle "
              "(max t rel diff %.3g, max uv diff %.3g), %zu near-ties, %zu edge grazes, %zu hard, "
              "%zu any-hit mismatches\n",
              what, c.rays, c.hits, c.equal, c.same_triangle, c.max_t_rel, c.max_uv, c.near_ties,
              c.edge_grazes, c.hard, c.any_mismatch);
}

void expect_gpu_agrees(const GpuComparison& c, const GpuRun& run) {
  EXPECT_TRUE(run.validation.empty()) << run.validation.front();
  EXPECT_EQ(c.hard, 0u);
  EXPECT_EQ(c.any_mismatch, 0u);
  // Ties and grazes are rare: rounding only decides rays aimed at edges and vertices.
  EXPECT_LE(c.near_ties + c.edge_grazes, c.rays / 100);
}

TEST(BvhGpu, TraversalMatchesCpuBruteForce) {
  auto gpu = Gpu::create(GpuOptions{});
  std::printf("[bvh gpu] device: %s (%s)\n", gpu->info().name.c_str(),
              gpu->info().driver_info.c_str());
  const auto no_seed = [](uint32_t) {};
  {
    const Soup soup = make_soup(11);
    const Bvh bvh = build_bvh(soup.scene);
    const std::vector<TestRay> rays = make_rays(soup, 12, 12000);
    const GpuRun run = run_gpu(*gpu, soup.scene, bvh, rays, 0);
    const GpuComparison c = compare_gpu(soup.scene, rays, run, {}, no_seed);
    print("centred", c);
    expect_gpu_agrees(c, run);
    EXPECT_GT(c.hits, c.rays / 2);
  }
  {
    const Soup soup = make_soup(13);
    const Vec3 offset{10000.0f, 2000.0f, -3000.0f};
    const FlatScene far = translated(soup.scene, offset);
    std::vector<TestRay> rays = make_rays(soup, 14, 12000);
    for (TestRay& r : rays) r.ray.origin = r.ray.origin + offset;
    const Bvh bvh = build_bvh(far);
    const GpuRun run = run_gpu(*gpu, far, bvh, rays, 0);
    const GpuComparison c = compare_gpu(far, rays, run, {}, no_seed);
    print("10 km", c);
    expect_gpu_agrees(c, run);
  }
}

TEST(BvhGpu, AlphaTestedTraversalMatchesCpu) {
  auto gpu = Gpu::create(GpuOptions{});
  Soup soup = make_soup(15);
  FlatScene& s = soup.scene;
  s.materials.resize(4, s.materials[0]);
  s.materials[1].alpha = uint32_t(AlphaKind::leaf_mask);
  s.materials[2].alpha = uint32_t(AlphaKind::checker_mask);
  s.materials[2].texture_scale = 4.0f;
  s.materials[3].alpha = uint32_t(AlphaKind::opacity);
  s.materials[3].opacity = 0.4f;
  s.instances.assign(4, GpuInstance{});
  for (uint32_t i = 0; i < 4; ++i) s.instances[i].material = i;
  for (uint32_t i = 0; i < s.triangles.size(); ++i) s.triangles[i].instance = i % 4;
  const Bvh bvh = build_bvh(s);
  const std::vector<TestRay> rays = make_rays(soup, 16, 10000);
  struct Ctx { const FlatScene* s; uint32_t seed; } ctx{&s, 0};
  const AlphaTest alpha{[](const void* u, uint32_t tri, float bu, float bv) {
                          const Ctx* c = static_cast<const Ctx*>(u);
                          return alpha_accept_default(*c->s, tri, bu, bv, c->seed);
                        },
                        &ctx};
  const GpuRun run = run_gpu(*gpu, s, bvh, rays, BVH_TEST_FLAG_ALPHA);
  const GpuComparison c = compare_gpu(s, rays, run, alpha, [&](uint32_t i) { ctx.seed = i; });
  print("alpha", c);
  expect_gpu_agrees(c, run);
  // The alpha path really ran: without it the GPU would report more hits than the CPU.
  const GpuRun opaque = run_gpu(*gpu, s, bvh, rays, 0);
  size_t alpha_hits = 0, opaque_hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    alpha_hits += run.hits[i].hit;
    opaque_hits += opaque.hits[i].hit;
  }
  EXPECT_LT(alpha_hits, opaque_hits);
}
#endif  // GIB_BVH_TEST_NO_GPU

}  // namespace
}  // namespace gib
