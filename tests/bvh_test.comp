#version 450
// GPU side of tests/test_bvh.cpp: traces each ray with trace_closest and trace_any from
// bvh.glsl and writes the results for comparison against the CPU reference.
#extension GL_GOOGLE_include_directive : require

#include "tests/bvh_test_shared.h"
#include "scene.glsl"

GIB_SCENE_BUFFERS(BVH_TEST_SET, BVH_TEST_BINDING_SCENE)

layout(std430, set = BVH_TEST_SET, binding = BVH_TEST_BINDING_RAYS) readonly buffer Rays {
  BvhTestRay rays[];
};
layout(std430, set = BVH_TEST_SET, binding = BVH_TEST_BINDING_HITS) writeonly buffer Hits {
  BvhTestHit hits[];
};
layout(push_constant) uniform Push { BvhTestPush pc; };

layout(local_size_x = BVH_TEST_WORKGROUP_SIZE) in;

#define GIB_ALPHA_TEST
#include "material.glsl"
#include "alpha_strategy.glsl"
#include "bvh.glsl"

uint g_alpha_seed;

bool gib_alpha_accept(uint triangle, float u, float v, inout uint calls, uint ray_key) {
  if ((pc.flags & BVH_TEST_FLAG_ALPHA) == 0u) return true;
  return gib_alpha_strategy_accept(triangle, u, v, calls, ray_key, g_alpha_seed, pc.alpha_strategy, pc.alpha_limit);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.ray_count) return;
  BvhTestRay ray = rays[i];
  g_alpha_seed = i;
  vec3 o = vec3(ray.ox, ray.oy, ray.oz);
  vec3 d = vec3(ray.dx, ray.dy, ray.dz);
  GibHit h;
  bool found = trace_closest(o, d, ray.tmin, ray.tmax, h);
  bool any = trace_any(o, d, ray.tmin, ray.tmax);
  BvhTestHit r;
  r.t = h.t;
  r.triangle = h.triangle;
  r.u = h.u;
  r.v = h.v;
  r.hit = found ? 1u : 0u;
  r.any_hit = any ? 1u : 0u;
  r.pad0 = 0u;
  r.pad1 = 0u;
  hits[i] = r;
}
