// Bounding volume hierarchy over a FlatScene's world-space triangles: binned SAH build on the
// CPU, flattened into GpuBvhNode (std430, mirrored in renderer/shaders/include/scene.glsl),
// traversed in GLSL by renderer/shaders/include/bvh.glsl and on the CPU by intersect_bvh.
//
// Node layout (32 bytes):
//   bmin, bmax        the node's box, rounded outward by one float ulp at build time so that
//                     flat boxes have volume and the slab test stays conservative.
//   count > 0         leaf: triangles tri_index[left_or_first .. left_or_first + count).
//   count == 0        interior: children at left_or_first and left_or_first + 1 (siblings are
//                     adjacent; a child index is always >= 1).
//   count == 0 and left_or_first == 0
//                     empty leaf; only the root of a BVH without valid triangles.
// Depth is kept below kBvhMaxDepth, so a traversal stack of kBvhMaxDepth entries never
// overflows.
//
// Triangles that cannot be hit are left out of the BVH entirely: non-finite vertices, and
// zero-area triangles (coincident or collinear vertices: the double-precision cross product of
// two edges is below 1e-14 of the product of their lengths). Floating point shear could give
// such a triangle a sliver of projected area; leaving them out guarantees they are never hit.
//
// Ray/triangle test: watertight (Woop, Benthin, Wald 2013): the ray is permuted so that its
// largest direction component is z, the vertices are sheared into ray space and the three 2D
// edge functions decide coverage; an edge function that rounds to exactly 0 is recomputed
// exactly (double on the CPU, Dekker's exact product on the GPU: the same float) so a ray
// through a shared edge or vertex hits at least one of the triangles sharing it.
// Accepted hits have tmin <= t <= tmax; among hits with equal t the lower original triangle id
// wins (on the CPU and the GPU), so results do not depend on the traversal order.
#pragma once
#include <cstdint>
#include <vector>

#include "renderer/scene/math.h"
#include "renderer/scene/scene.h"

namespace gib {

struct GpuBvhNode {  // 32 bytes, std430
  float bmin[3];
  uint32_t left_or_first;
  float bmax[3];
  uint32_t count;
};
static_assert(sizeof(GpuBvhNode) == 32);

inline constexpr uint32_t kBvhMaxDepth = 64;   // == GIB_BVH_STACK_SIZE in bvh.glsl
inline constexpr uint32_t kBvhMaxLeafSize = 4;  // leaves never hold more (SAH may stop earlier)

struct BvhStats {
  uint32_t triangles = 0;          // in the BVH (valid)
  uint32_t skipped_triangles = 0;  // zero-area or non-finite, never hit
  uint32_t nodes = 0;
  uint32_t leaves = 0;
  uint32_t max_depth = 0;          // root = 0
  float sah_cost = 0;              // sum of node areas / root area, traversal 1, triangle 1
  double build_ms = 0;
};

struct Bvh {
  std::vector<GpuBvhNode> nodes;    // root at 0
  std::vector<uint32_t> tri_index;  // leaf slot -> original triangle id (GpuTriangle index)
  // CPU-only copy of the three vertex positions of each leaf slot (9 floats per slot, in
  // tri_index order), so intersect_bvh reads memory linearly. Not uploaded.
  std::vector<float> slot_positions;
  BvhStats stats;
};

Bvh build_bvh(const FlatScene& scene);

struct Ray {
  Vec3 origin;
  Vec3 dir;  // need not be normalised; t is in units of dir
};

struct Hit {
  float t = 0;
  uint32_t triangle = 0;  // original triangle id
  float u = 0, v = 0;     // barycentrics of the triangle's second and third vertex
  bool hit = false;
};

// Called for a candidate that would otherwise be accepted; return false to ignore it (alpha
// testing). Mirrors gib_alpha_accept in bvh.glsl.
struct AlphaTest {
  bool (*accept)(const void* user, uint32_t triangle, float u, float v) = nullptr;
  const void* user = nullptr;
};

// Reference: every triangle, same test, same tie rule.
Hit intersect_brute_force(const FlatScene& scene, Ray ray, float tmin, float tmax,
                          AlphaTest alpha = {});
Hit intersect_bvh(const Bvh& bvh, const FlatScene& scene, Ray ray, float tmin, float tmax,
                  AlphaTest alpha = {});
bool occluded_bvh(const Bvh& bvh, const FlatScene& scene, Ray ray, float tmin, float tmax,
                  AlphaTest alpha = {});
// One triangle, no t interval: the watertight test alone (hit false on a miss or a parallel
// ray). Tests use it to check that a hit reported by the GPU is a real hit.
Hit intersect_triangle(const FlatScene& scene, uint32_t triangle, Ray ray);
// True when the triangle is left out of the BVH (zero area or non-finite).
bool triangle_is_degenerate(const FlatScene& scene, uint32_t triangle);

}  // namespace gib
