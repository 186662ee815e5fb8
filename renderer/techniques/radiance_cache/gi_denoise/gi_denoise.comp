#version 460
#extension GL_GOOGLE_include_directive : require
// gi_denoise, one direction of the separable bilateral gaussian per dispatch (see gi_denoise.h).
// The group's row
// (horizontal) or column (vertical) of taps, its 8 x 8 pixels plus radius either side along the
// axis, is loaded into group-shared memory once (geometry, hit distance, SH, direct part), then
// each pixel filters from there.
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise.glsl"

// kDenoiseGroup lines across the axis, each kTileLen taps along it: tap a of line c (slot
// c * kTileLen + a) is gather pixel origin + (a - radius) * axis + c * across. Values are kept as
// loaded (32-bit floats), so the arithmetic is the one done on image loads. 30 KiB at radius 16.
const int kTileLen = int(kDenoiseGroup) + 2 * kRadius;
const int kTileSize = int(kDenoiseGroup) * kTileLen;
shared vec4 s_pos[kTileSize];
shared vec4 s_nh[kTileSize];  // xyz normal, w hit distance
shared vec4 s_r[kTileSize];
shared vec4 s_g[kTileSize];
shared vec4 s_b[kTileSize];
shared vec4 s_d[kTileSize];

void main() {
  ivec2 axis = ivec2(push.axis_x, push.axis_y), across = ivec2(1) - axis;
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * int(kDenoiseGroup);
  // Consecutive invocations load consecutive pixels along x in both directions.
  for (int i = int(gl_LocalInvocationIndex); i < kTileSize; i += int(kDenoiseGroup * kDenoiseGroup)) {
    int a = axis.x != 0 ? i % kTileLen : i / int(kDenoiseGroup);
    int c = axis.x != 0 ? i / kTileLen : i % int(kDenoiseGroup);
    int slot = c * kTileLen + a;
    ivec2 q = origin + (a - kRadius) * axis + c * across;
    vec4 pos, nh, r, g, b, d;
    denoise_geometry(q, pos, nh);
    denoise_values(q, r, g, b, d);
    s_pos[slot] = pos;
    s_nh[slot] = nh;
    s_r[slot] = r;
    s_g[slot] = g;
    s_b[slot] = b;
    s_d[slot] = d;
  }
  barrier();

  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, imageSize(out_r)))) return;
  ivec2 l = ivec2(gl_LocalInvocationID.xy);
  int centre = (axis.x != 0 ? l.y : l.x) * kTileLen + (axis.x != 0 ? l.x : l.y) + kRadius;
  vec4 r = vec4(0.0), gg = vec4(0.0), b = vec4(0.0), d = vec4(0.0);
  if (s_pos[centre].w != 0.0) {  // a sky gather pixel is written as 0
    float inv_two_sigma2 = denoise_inv_two_sigma2();
    int radius = int(push.radius);
    DenoiseSums s = denoise_sums();
    for (int k = -radius; k <= radius; ++k) {
      int t = centre + k;
      float w, wd;
      if (denoise_weights(s_pos[centre], s_nh[centre], s_pos[t], s_nh[t], k, inv_two_sigma2, w, wd))
        denoise_add(s, w, wd, s_r[t], s_g[t], s_b[t], s_d[t]);
    }
    denoise_result(s, r, gg, b, d);
  }
  imageStore(out_r, g, r);
  imageStore(out_g, g, gg);
  imageStore(out_b, g, b);
  imageStore(out_direct, g, d);
}
