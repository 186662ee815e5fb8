#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/vrcs_rate/vrcs_rate_shared.h"
#include "renderer/techniques/deferred/include/deferred_attributes.glsl"

// One workgroup per 8x8 rate tile.
layout(local_size_x = kVrcsTile, local_size_y = kVrcsTile) in;
layout(set = 0, binding = kVrcsBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kVrcsBindTangentFrame, rgba16f) uniform readonly image2D in_frame;
layout(set = 0, binding = kVrcsBindPrevLuma, r32f) uniform readonly image2D prev_luma;
layout(std430, set = 0, binding = kVrcsBindRates) buffer Rates { uint rates[]; };
layout(push_constant) uniform Push { VrcsPush push; };

shared uint tile_ok;  // bit 0: every x pair alike, bit 1: every y pair
// Each invocation's luminance step to its pair partner (x pairs, y pairs; 0 where it has none).
shared float step_x[kVrcsTile * kVrcsTile], step_y[kVrcsTile * kVrcsTile];

// Last frame's tone-mapped luminance (gib_vrcs_luma; NaN: the pair is not alike).
float tone_luma(ivec2 p) { return imageLoad(prev_luma, p).r; }

// The normal of p from the tangent frame (z's sign is not stored here: x, y are enough to see a
// crease between two facing-the-camera normals, and both signs' z have the same magnitude).
vec3 frame_normal(ivec2 p) {
  vec2 xy = imageLoad(in_frame, p).xy;
  return vec3(xy, sqrt(max(0.0, 1.0 - dot(xy, xy))));
}

// Whether a and b may share a result, by geometry; `step` gets their luminance step (NaN or Inf
// in either: never alike).
bool alike(ivec2 a, ivec2 b, out float step) {
  step = 0.0;
  ivec2 size = imageSize(vbuffer);
  if (any(greaterThanEqual(b, size))) return true;  // off screen: nothing to share with
  step = abs(tone_luma(a) - tone_luma(b));
  if (!(step <= 1.0)) return false;
  if (push.edges == 0u) return true;
  uvec2 ia = imageLoad(vbuffer, a).xy, ib = imageLoad(vbuffer, b).xy;
  if ((ia.x == kVisibilityNone) != (ib.x == kVisibilityNone)) return false;
  if (ia.x == kVisibilityNone) return true;
  if (ia.y != ib.y) return false;
  return dot(frame_normal(a), frame_normal(b)) >= 0.9063;  // 25 degrees
}

void main() {
  if (gl_LocalInvocationIndex == 0u) tile_ok = kVrcsCoarseX | kVrcsCoarseY;
  barrier();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(p, imageSize(vbuffer)));
  uint ok = kVrcsCoarseX | kVrcsCoarseY;
  float sx = 0.0, sy = 0.0;
  if (inside && (p.x & 1) == 0 && !alike(p, p + ivec2(1, 0), sx)) ok &= ~kVrcsCoarseX;
  if (inside && (p.y & 1) == 0 && !alike(p, p + ivec2(0, 1), sy)) ok &= ~kVrcsCoarseY;
  step_x[gl_LocalInvocationIndex] = sx;
  step_y[gl_LocalInvocationIndex] = sy;
  if (ok != (kVrcsCoarseX | kVrcsCoarseY)) atomicAnd(tile_ok, ok);
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    // The error of sharing one result per pair, as Yang et al. (2019, content adaptive shading)
    // estimate it: the mean luminance step over the tile's pairs in that direction, in a fixed
    // order (deterministic). A lone noisy pair does not force full rate; an edge through the
    // tile (a quarter of its pairs stepping by 0.1) does.
    float mean_x = 0.0, mean_y = 0.0;
    for (uint i = 0u; i < kVrcsTile * kVrcsTile; ++i) {
      mean_x += step_x[i];
      mean_y += step_y[i];
    }
    const float pairs = float(kVrcsTile * kVrcsTile / 2u);
    uint luma_ok = (mean_x / pairs <= push.threshold ? kVrcsCoarseX : 0u) | (mean_y / pairs <= push.threshold ? kVrcsCoarseY : 0u);
    uint rate = push.history != 0u ? tile_ok & luma_ok : 0u;
    if (push.force != 0u) rate = push.force;
    rates[kVrcsHeader + gl_WorkGroupID.x + gl_WorkGroupID.y * push.rate_tiles_x] = rate;
    atomicAdd(rates[kVrcsStats + kVrcsStatTiles + rate], 1u);
  }
}
