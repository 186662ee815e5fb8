// bvh.glsl with the per-frame stochastic alpha test (gib_alpha_accept_default, re-rolled every
// frame per triangle) switched by a specialisation constant kHasAlpha (scenes without alpha-tested
// materials compile it out). Define GIB_ALPHA_SPEC to the pass's constant id, then include after
// frame.glsl, hash.glsl and material.glsl:
//   #define GIB_ALPHA_SPEC kGatherSpecAlpha
//   #include "bvh_alpha.glsl"
#ifndef GIB_BVH_ALPHA_GLSL
#define GIB_BVH_ALPHA_GLSL
layout(constant_id = GIB_ALPHA_SPEC) const bool kHasAlpha = true;
#define GIB_ALPHA_TEST
#include "alpha_strategy.glsl"
// The run's alpha strategy (frame constants' alpha_info: Settings::alpha) at every candidate.
bool gib_alpha_accept(uint triangle, float u, float v, inout uint calls, uint ray_key) {
  return !kHasAlpha || gib_alpha_strategy_accept(triangle, u, v, calls, ray_key, gib_pcg(triangle ^ gib_frame_index()),
                                                 gib_frame.alpha_info.x, gib_frame.alpha_info.y);
}
#include "bvh.glsl"
#endif  // GIB_BVH_ALPHA_GLSL
