#version 460
#extension GL_GOOGLE_include_directive : require
// One direction of the separable bilateral gaussian over the gather SH and the gather's direct
// part, with the same weights (see gi_denoise.h).
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "finite.glsl"

layout(local_size_x = kDenoiseGroup, local_size_y = kDenoiseGroup) in;
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

// Geometry of gather pixel g: its representative full-res pixel's position (w: distance to the
// camera, 0 for sky) and normal.
void gather_geometry(ivec2 g, out vec4 pos, out vec3 n) {
  int div = int(push.divisor);
  ivec2 p = min(g * div + div / 2, imageSize(gb_position) - 1);
  pos = imageLoad(gb_position, p);
  n = imageLoad(gb_normal, p).xyz;
}

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_r);
  if (any(greaterThanEqual(g, size))) return;
  vec4 pos_c;
  vec3 n_c;
  gather_geometry(g, pos_c, n_c);
  if (pos_c.w == 0.0) {
    imageStore(out_r, g, vec4(0.0));
    imageStore(out_g, g, vec4(0.0));
    imageStore(out_b, g, vec4(0.0));
    imageStore(out_direct, g, vec4(0.0));
    return;
  }
  float h_c = imageLoad(in_hit, g).x;
  int radius = int(push.radius);
  float inv_two_sigma2 = radius > 0 ? 2.0 / float(radius * radius) : 0.0;  // sigma = radius / 2
  ivec2 axis = ivec2(push.axis_x, push.axis_y);
  vec4 sum_r = vec4(0.0), sum_g = vec4(0.0), sum_b = vec4(0.0), sum_d = vec4(0.0);
  float sum_w = 0.0, sum_wd = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    ivec2 q = g + k * axis;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    vec4 pos_q;
    vec3 n_q;
    gather_geometry(q, pos_q, n_q);
    if (pos_q.w == 0.0) continue;
    float h_q = imageLoad(in_hit, q).x;
    float wd = exp(-float(k * k) * inv_two_sigma2);  // geometry: the direct part's weight
    wd *= pow(max(0.0, dot(n_c, n_q)), kDenoiseNormalPower);
    wd *= exp(-abs(dot(n_c, pos_q.xyz - pos_c.xyz)) / (pos_c.w * kDenoiseDepthSigma));
    float w = wd;
    if (push.hit_weight != 0u) {
      float dh = abs(h_q - h_c) / max(max(h_q, h_c), 1e-6);
      w *= exp(-(dh * dh) / (kDenoiseHitSigma * kDenoiseHitSigma));
    }
    if (wd <= 0.0) continue;
    vec4 tr = imageLoad(in_r, q), tg = imageLoad(in_g, q), tb = imageLoad(in_b, q), td = imageLoad(in_direct, q);
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
