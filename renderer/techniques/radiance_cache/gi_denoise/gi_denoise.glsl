// gi_denoise.comp's bindings and the weight and accumulation of one tap (see gi_denoise.h,
// gi_denoise_shared.h), apart from the group-shared tile that feeds them.
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "finite.glsl"

layout(local_size_x = kDenoiseGroup, local_size_y = kDenoiseGroup) in;
// denoise_radius: sizes the group-shared tile. The weights take the radius from the push
// constants (the same value): with a compile-time radius the compiler could fold exp() at build
// time, with another rounding than the device's.
layout(constant_id = kDenoiseSpecRadius) const int kRadius = 3;
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

// Gather pixel q's geometry (its representative full-res pixel's position, w: distance, 0 for
// sky, and normal; final_gather's convention) and hit distance, or position 0 (skipped as a sky
// tap is) when q is outside the image.
void denoise_geometry(ivec2 q, out vec4 pos, out vec4 normal_hit) {
  pos = vec4(0.0);
  normal_hit = vec4(0.0);
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, imageSize(out_r)))) return;
  int div = int(push.divisor);
  ivec2 p = min(q * div + div / 2, imageSize(gb_position) - 1);
  pos = imageLoad(gb_position, p);
  normal_hit = vec4(imageLoad(gb_normal, p).xyz, imageLoad(in_hit, q).x);
}

// Gather pixel q's SH (r, g, b) and direct part, or 0 outside the image.
void denoise_values(ivec2 q, out vec4 r, out vec4 g, out vec4 b, out vec4 d) {
  r = g = b = d = vec4(0.0);
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, imageSize(out_r)))) return;
  r = imageLoad(in_r, q);
  g = imageLoad(in_g, q);
  b = imageLoad(in_b, q);
  d = imageLoad(in_direct, q);
}

float denoise_inv_two_sigma2() {
  int radius = int(push.radius);
  return radius > 0 ? 2.0 / float(radius * radius) : 0.0;  // sigma = radius / 2
}

// The weights of tap q at k taps from centre c (geometry and hit distance as denoise_geometry
// gives them): w for the SH, wd (geometry only) for the direct part. False: the tap is skipped
// (sky, outside the image, or zero geometry weight; a NaN weight is not skipped here).
bool denoise_weights(vec4 pos_c, vec4 nh_c, vec4 pos_q, vec4 nh_q, int k, float inv_two_sigma2,
                     out float w, out float wd) {
  w = wd = 0.0;
  if (pos_q.w == 0.0) return false;
  vec3 n_c = nh_c.xyz, n_q = nh_q.xyz;
  float h_c = nh_c.w, h_q = nh_q.w;
  wd = exp(-float(k * k) * inv_two_sigma2);  // geometry: the direct part's weight
  wd *= pow(max(0.0, dot(n_c, n_q)), kDenoiseNormalPower);
  wd *= exp(-abs(dot(n_c, pos_q.xyz - pos_c.xyz)) / (pos_c.w * kDenoiseDepthSigma));
  w = wd;
  if (push.hit_weight != 0u) {
    float dh = abs(h_q - h_c) / max(max(h_q, h_c), 1e-6);
    w *= exp(-(dh * dh) / (kDenoiseHitSigma * kDenoiseHitSigma));
  }
  return !(wd <= 0.0);
}

struct DenoiseSums {
  vec4 r, g, b, d;
  float w, wd;
};

DenoiseSums denoise_sums() { return DenoiseSums(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), 0.0, 0.0); }

// Adds a tap's SH and direct part. Guard: a tap whose weight (a NaN normal) or value is not
// finite is skipped: weight 0 would not do, 0 x NaN is NaN.
void denoise_add(inout DenoiseSums s, float w, float wd, vec4 tr, vec4 tg, vec4 tb, vec4 td) {
  if (push.nan_guards != 0u &&
      !(gib_finite(w) && gib_finite(wd) && gib_finite(tr) && gib_finite(tg) && gib_finite(tb) && gib_finite(td)))
    return;
  s.r += w * tr;
  s.g += w * tg;
  s.b += w * tb;
  s.w += w;
  s.d += wd * td;
  s.wd += wd;
}

// The filtered SH (r, g, b) and direct part. The centre's own weight is 1 (k = 0, identical
// geometry), so s.w >= 1, unless guards skipped it (then every tap may be gone and it is 0).
void denoise_result(DenoiseSums s, out vec4 r, out vec4 g, out vec4 b, out vec4 d) {
  float inv = 1.0 / max(s.w, 1e-6);
  r = s.r * inv;
  g = s.g * inv;
  b = s.b * inv;
  d = s.d / max(s.wd, 1e-6);
}
