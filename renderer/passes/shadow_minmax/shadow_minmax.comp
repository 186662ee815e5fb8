#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/shadow_minmax/shadow_minmax_shared.h"
#include "frame.glsl"
#include "shadow_cascades.glsl"

layout(local_size_x = kShadowGroup, local_size_y = kShadowGroup) in;
layout(set = 0, binding = kMinMaxBindTiles, rg32f) uniform readonly image2D src;
layout(set = 0, binding = kShadowBindMinMax, rg32f) uniform writeonly image2D dst;
layout(push_constant) uniform Push { ShadowCascadePush push; };

// Dilates the block min/max by the filter, one axis per dispatch (x, then y: a square's min/max
// is the min/max over its rows of each row's): every texel a receiver in this block can tap
// (disk of the area-light radius, one more texel for the bilinear footprint) lies within k
// blocks, k rounded up, of the same cascade. Conservative: a pixel this calls fully lit or
// shadowed is.
void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, imageSize(dst)))) return;
  int tiles = int(push.params.y) / int(kShadowMinMaxTile);
  int cascade = t.x / tiles;
  vec3 cam, fwd;
  float tan_y, aspect;
  csm_camera(cam, fwd, tan_y, aspect);
  ShadowBasis b = csm_shadow_basis(gib_frame.sun_dir.xyz);
  ShadowCascade c = csm_cascade(uint(cascade), cam, fwd, tan_y, aspect, b, push);
  float radius_tex = max(1.0, csm_filter_radius(push) / csm_texel_size(c, push));
  int k = int(ceil((radius_tex + 1.0) / float(kShadowMinMaxTile)));
  ivec2 lo_t = ivec2(cascade * tiles, 0), hi_t = ivec2(cascade * tiles + tiles - 1, tiles - 1);
  ivec2 axis = push.counts.z != 0u ? ivec2(1, 0) : ivec2(0, 1);  // 1: along x
  float lo = 1.0, hi = 0.0;
  for (int i = -k; i <= k; ++i) {
    vec2 mm = imageLoad(src, clamp(t + axis * i, lo_t, hi_t)).xy;
    lo = min(lo, mm.x);
    hi = max(hi, mm.y);
  }
  imageStore(dst, t, vec4(lo, hi, 0.0, 0.0));
}
