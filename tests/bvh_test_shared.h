// Shared by tests/test_bvh.cpp and tests/bvh_test.comp: bindings, workgroup size, push
// constants and the ray / hit records of the GPU traversal test.
//
// Set 0: bindings 0..6 are the scene buffers in GIB_SCENE_BUFFERS order (scene.glsl), then
// the rays (read) and the hits (written), one hit per ray.
#ifndef GIB_BVH_TEST_SHARED_H
#define GIB_BVH_TEST_SHARED_H

#ifdef __cplusplus
#include <cstdint>
namespace gib::bvh_test {
using uint = uint32_t;
#endif

#define BVH_TEST_SET 0
#define BVH_TEST_BINDING_SCENE 0
#define BVH_TEST_BINDING_RAYS 7
#define BVH_TEST_BINDING_HITS 8
#define BVH_TEST_WORKGROUP_SIZE 64

// Push constant flags.
#define BVH_TEST_FLAG_ALPHA 1u  // alpha: gib_alpha_strategy_accept (strategy, limit) with seed = ray index

struct BvhTestRay {  // 32 bytes
  float ox, oy, oz, tmin;
  float dx, dy, dz, tmax;
};

struct BvhTestHit {  // 32 bytes
  float t;            // closest hit; tmax when none
  uint triangle;      // original triangle id; 0xffffffff when none
  float u, v;
  uint hit;           // trace_closest returned true
  uint any_hit;       // trace_any returned true
  uint pad0, pad1;
};

struct BvhTestPush {
  uint ray_count;
  uint flags;
  uint alpha_strategy;  // with BVH_TEST_FLAG_ALPHA (alpha_strategy.glsl)
  uint alpha_limit;
};

#ifdef __cplusplus
static_assert(sizeof(BvhTestRay) == 32 && sizeof(BvhTestHit) == 32);
}  // namespace gib::bvh_test
#endif

#endif  // GIB_BVH_TEST_SHARED_H
