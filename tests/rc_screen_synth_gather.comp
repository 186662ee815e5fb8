#version 460
#extension GL_GOOGLE_include_directive : require
// Writes gather_sh_* (L0 = low or high by the gather pixel's surface height, plus per-pixel
// noise; L1 = 0), gather_direct (rgb = the same value) and a constant gather_hit_distance, so
// gi_denoise can be tested on known input; optionally a NaN in some pixels' SH (nan_every).
#include "tests/rc_screen_synth_gather_shared.h"
#include "hash.glsl"
layout(local_size_x = kSynthGroup, local_size_y = kSynthGroup) in;
layout(set = 0, binding = kSynthBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kSynthBindShR, rgba16f) uniform writeonly image2D out_r;
layout(set = 0, binding = kSynthBindShG, rgba16f) uniform writeonly image2D out_g;
layout(set = 0, binding = kSynthBindShB, rgba16f) uniform writeonly image2D out_b;
layout(set = 0, binding = kSynthBindHit, r32f) uniform writeonly image2D out_hit;
layout(set = 0, binding = kSynthBindDirect, rgba16f) uniform writeonly image2D out_direct;
layout(push_constant) uniform Push { SynthPush push; };
void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, imageSize(out_hit)))) return;
  int div = int(push.divisor);
  vec4 pos = imageLoad(gb_position, min(g * div + div / 2, imageSize(gb_position) - 1));
  float base = pos.y > push.split_y ? push.high : push.low;
  float n = (float(gib_pcg(uint(g.x) * 7919u + uint(g.y) * 104729u) >> 8) / 16777216.0 * 2.0 - 1.0) * push.noise;
  vec4 v = pos.w == 0.0 ? vec4(0.0) : vec4(base + n, 0.0, 0.0, 0.0);
  bool nan = push.nan_every != 0u && pos.w != 0.0 && uint(g.x + 7 * g.y) % push.nan_every == 0u;
  imageStore(out_r, g, nan ? vec4(v.x, uintBitsToFloat(0x7fc00000u), 0.0, 0.0) : v);
  imageStore(out_g, g, v);
  imageStore(out_b, g, v);
  imageStore(out_direct, g, vec4(v.xxx, 0.0));
  imageStore(out_hit, g, vec4(pos.w == 0.0 ? 0.0 : 1.0));
}
