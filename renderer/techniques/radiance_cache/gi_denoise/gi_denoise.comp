#version 460
#extension GL_GOOGLE_include_directive : require
// One direction of the separable bilateral gaussian over the gather SH and the gather's direct
// part, with the same weights (see gi_denoise.h). The group's row (horizontal) or column
// (vertical) of taps, its 8 x 8 pixels plus kRadius either side along the axis, is loaded into
// group-shared memory once (every tap's geometry, hit distance, SH and direct part), then each
// pixel filters from there: a tap is read from global memory once per group, not 2 radius + 1
// times, and the geometry of a gather pixel (two scattered full-res loads) once per group.
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "finite.glsl"

layout(local_size_x = kDenoiseGroup, local_size_y = kDenoiseGroup) in;
layout(constant_id = kDenoiseSpecRadius) const int kRadius = 3;  // denoise_radius
layout(set = 0, binding = kDenoiseBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kDenoiseBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kDenoiseBindHit, r32f) uniform readonly image2D in_hit;
layout(set = 0, binding = kDenoiseBindInR, rgba16f) uniform readonly image2D in_r;
layout(set = 0, binding = kDenoiseBindInG, rgba16f) uniform readonly image2D in_g;
layout(set = 0, binding = kDenoiseBindInB, rgba16f) uniform readonly image2D in_b;
layout(set = 0, binding = kDenoiseBindOutR, rgba16f) uniform writeonly image2D out_r;
layout(set = 0, binding = kDenoiseBindOutG, rgba16f) uniform writeonly image2D out_g;
layout(set = 0, binding = kDenoiseBindOutB, rgba16f) uniform writeonly image2D out_b;
layout(set = 0, binding = kDenoiseBindInDirect, rgba16f) uniform readonly image2D in_direct;
layout(set = 0, binding = kDenoiseBindOutDirect, rgba16f) uniform writeonly image2D out_direct;
layout(push_constant) uniform Push { DenoisePush push; };

// The tile: kDenoiseGroup lines across the axis, each kTileLen taps along it; tap a of line c
// (slot c * kTileLen + a) is gather pixel origin + (a - kRadius) * axis + c * across. Values are
// kept as loaded (32-bit floats; the 16-bit images convert exactly), so the filter's arithmetic
// is the one it did on image loads. A tap outside the image gets position w = 0, as a sky tap:
// both are skipped before anything else is read.
const int kTileLen = int(kDenoiseGroup) + 2 * kRadius;
const int kTileSize = int(kDenoiseGroup) * kTileLen;
shared vec4 s_pos[kTileSize];     // representative full-res position (w: distance, 0 sky)
shared vec4 s_normal[kTileSize];  // xyz: representative full-res normal, w: gather hit distance
shared vec4 s_r[kTileSize];
shared vec4 s_g[kTileSize];
shared vec4 s_b[kTileSize];
shared vec4 s_d[kTileSize];

void load_tap(int slot, ivec2 q, ivec2 size) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
    s_pos[slot] = vec4(0.0);
    return;
  }
  // Geometry of gather pixel q: its representative full-res pixel's (final_gather's convention).
  int div = int(push.divisor);
  ivec2 p = min(q * div + div / 2, imageSize(gb_position) - 1);
  s_pos[slot] = imageLoad(gb_position, p);
  s_normal[slot] = vec4(imageLoad(gb_normal, p).xyz, imageLoad(in_hit, q).x);
  s_r[slot] = imageLoad(in_r, q);
  s_g[slot] = imageLoad(in_g, q);
  s_b[slot] = imageLoad(in_b, q);
  s_d[slot] = imageLoad(in_direct, q);
}

void main() {
  ivec2 size = imageSize(out_r);
  ivec2 axis = ivec2(push.axis_x, push.axis_y), across = ivec2(1) - axis;
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * int(kDenoiseGroup);
  // Consecutive invocations load consecutive pixels along x in both directions (coalesced).
  for (int i = int(gl_LocalInvocationIndex); i < kTileSize; i += int(kDenoiseGroup * kDenoiseGroup)) {
    int a = axis.x != 0 ? i % kTileLen : i / int(kDenoiseGroup);
    int c = axis.x != 0 ? i / kTileLen : i % int(kDenoiseGroup);
    load_tap(c * kTileLen + a, origin + (a - kRadius) * axis + c * across, size);
  }
  barrier();

  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, size))) return;
  ivec2 l = ivec2(gl_LocalInvocationID.xy);
  int centre = (axis.x != 0 ? l.y : l.x) * kTileLen + (axis.x != 0 ? l.x : l.y) + kRadius;
  vec4 pos_c = s_pos[centre];
  if (pos_c.w == 0.0) {
    imageStore(out_r, g, vec4(0.0));
    imageStore(out_g, g, vec4(0.0));
    imageStore(out_b, g, vec4(0.0));
    imageStore(out_direct, g, vec4(0.0));
    return;
  }
  vec3 n_c = s_normal[centre].xyz;
  float h_c = s_normal[centre].w;
  // The weights take the radius from the push constants (equal to kRadius), as before the tile:
  // a compile-time radius would let the compiler fold exp() at build time, with another rounding.
  int radius = int(push.radius);
  float inv_two_sigma2 = radius > 0 ? 2.0 / float(radius * radius) : 0.0;  // sigma = radius / 2
  vec4 sum_r = vec4(0.0), sum_g = vec4(0.0), sum_b = vec4(0.0), sum_d = vec4(0.0);
  float sum_w = 0.0, sum_wd = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    int t = centre + k;
    vec4 pos_q = s_pos[t];
    if (pos_q.w == 0.0) continue;  // sky, or outside the image
    vec3 n_q = s_normal[t].xyz;
    float h_q = s_normal[t].w;
    float wd = exp(-float(k * k) * inv_two_sigma2);  // geometry: the direct part's weight
    wd *= pow(max(0.0, dot(n_c, n_q)), kDenoiseNormalPower);
    wd *= exp(-abs(dot(n_c, pos_q.xyz - pos_c.xyz)) / (pos_c.w * kDenoiseDepthSigma));
    float w = wd;
    if (push.hit_weight != 0u) {
      float dh = abs(h_q - h_c) / max(max(h_q, h_c), 1e-6);
      w *= exp(-(dh * dh) / (kDenoiseHitSigma * kDenoiseHitSigma));
    }
    if (wd <= 0.0) continue;
    vec4 tr = s_r[t], tg = s_g[t], tb = s_b[t], td = s_d[t];
    // Guard: skip a tap whose weight (a NaN normal) or value is not finite: weight 0 would
    // not do, 0 x NaN is NaN.
    if (push.nan_guards != 0u &&
        !(gib_finite(w) && gib_finite(wd) && gib_finite(tr) && gib_finite(tg) && gib_finite(tb) && gib_finite(td)))
      continue;
    sum_r += w * tr;
    sum_g += w * tg;
    sum_b += w * tb;
    sum_w += w;
    sum_d += wd * td;
    sum_wd += wd;
  }
  // The centre's own weight is 1 (k = 0, identical geometry), so sum_w >= 1, unless guards
  // skipped it (then every tap may be gone and the result is 0).
  float inv = 1.0 / max(sum_w, 1e-6);
  imageStore(out_r, g, sum_r * inv);
  imageStore(out_g, g, sum_g * inv);
  imageStore(out_b, g, sum_b * inv);
  imageStore(out_direct, g, sum_d / max(sum_wd, 1e-6));
}
