// pixel_denoise: spatial + temporal filtering of the per-pixel SH, then a Poisson disc for
// disoccluded pixels (see pixel_denoise.h). Two kernels chosen by kKernel.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise_shared.h"
#include "frame.glsl"
#include "hash.glsl"
#include "finite.glsl"
#include "ycocg_sh.glsl"
layout(constant_id = kPvDenoiseSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"
layout(set = 0, binding = kPvDenoiseBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvDenoiseBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvDenoiseBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
#include "renderer/techniques/probe_volume/include/pv_surface.glsl"
layout(set = 0, binding = kPvDenoiseBindSh, rg32ui) uniform readonly uimage2D in_sh;
layout(set = 0, binding = kPvDenoiseBindPrevY, rgba32f) uniform readonly image2D prev_y;
layout(set = 0, binding = kPvDenoiseBindPrevC, rgba32f) uniform readonly image2D prev_c;
layout(set = 0, binding = kPvDenoiseBindHistoryY, rgba32f) uniform image2D history_y;
layout(set = 0, binding = kPvDenoiseBindHistoryC, rgba32f) uniform image2D history_c;
layout(set = 0, binding = kPvDenoiseBindGiY, rgba32f) uniform writeonly image2D gi_y;
layout(set = 0, binding = kPvDenoiseBindGiC, rgba32f) uniform writeonly image2D gi_c;
layout(local_size_x = kPvDenoiseGroup, local_size_y = kPvDenoiseGroup) in;

// A sample (Y0 re-evaluated for normal n, Y1, Co, Cg) in `y` and `c` (c.zw unused).
void decode_at(ivec2 q, vec3 n, vec3 n0, out vec4 y, out vec2 c) {
  float y0;
  vec3 y1;
  vec2 cocg;
  gib_unpack_ycocg_sh(imageLoad(in_sh, q).xy, y0, y1, cocg);
  float y_n = y0 > 0.0 ? pv_y_for_normal(y0, y1, n, n0) : 0.0;
  y = vec4(y_n, y1);
  c = y0 > 0.0 ? cocg * (y_n / y0) : vec2(0.0);
}

void filter_pixel(ivec2 q, ivec2 size) {
  PvSurface a = pv_surface_at(pv_source_pixel(q));
  if (a.depth == 0.0) {
    imageStore(history_y, q, vec4(0.0));
    imageStore(history_c, q, vec4(0.0));
    return;
  }
  int r = int(pv.flags.w & 0xffffu);
  vec4 sum_y = vec4(0.0);
  vec2 sum_c = vec2(0.0);
  float sum_w = 0.0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      ivec2 q2 = q + ivec2(dx, dy);
      if (any(lessThan(q2, ivec2(0))) || any(greaterThanEqual(q2, size))) continue;
      PvSurface b = pv_surface_at(pv_source_pixel(q2));
      float w = (dx == 0 && dy == 0) ? 1.0 : pv_bilateral(a, b);
      if (w <= 0.0) continue;
      vec4 y;
      vec2 c;
      decode_at(q2, a.normal, b.normal, y, c);
      sum_y += w * y;
      sum_c += w * c;
      sum_w += w;
    }
  vec4 y = sum_y / sum_w;
  vec2 c = sum_c / sum_w;
  // Temporal: last frame's history at this surface's reprojected ray pixel, when its view
  // depth agrees within 5%.
  vec4 clip = gib_frame.view_proj * vec4(a.position, 1.0);
  vec4 prev = gib_frame.prev_view_proj * vec4(a.position, 1.0);
  float frames = 1.0;
  uint n_max = max(pv.flags.w >> 16u, 1u);
  if (prev.w > 0.0 && n_max > 1u) {
    vec2 uv = prev.xy / prev.w * 0.5 + 0.5;
    ivec2 qp = ivec2(floor(uv * vec2(gib_render_size()) / float(pv_divisor())));
    if (all(greaterThanEqual(qp, ivec2(0))) && all(lessThan(qp, size))) {
      vec4 hc = imageLoad(prev_c, qp);
      if (hc.z > 0.0 && abs(hc.w - prev.w) < 0.05 * prev.w) {
        frames = min(hc.z + 1.0, float(n_max));
        float alpha = 1.0 / frames;
        y = mix(imageLoad(prev_y, qp), y, alpha);
        c = mix(hc.xy, c, alpha);
      }
    }
  }
  if (pv_flag(kPvFlagNanGuards) && !(gib_finite(y) && gib_finite(c))) {
    y = vec4(0.0);
    c = vec2(0.0);
    frames = 0.0;
  }
  imageStore(history_y, q, y);
  imageStore(history_c, q, vec4(c, frames, clip.w));
}

// Poisson disc (unit radius), 8 taps.
const vec2 kPoisson[kPvPoissonTaps] = vec2[](vec2(-0.613, 0.617), vec2(0.170, -0.040), vec2(-0.299, 0.791),
                                             vec2(0.645, 0.493), vec2(-0.651, -0.717), vec2(0.421, 0.027),
                                             vec2(-0.817, -0.271), vec2(0.977, -0.132));

void poisson_pixel(ivec2 q, ivec2 size) {
  vec4 y = imageLoad(history_y, q);
  vec4 c = imageLoad(history_c, q);
  int r = int(pv.flags.w & 0xffffu);
  if (c.z == 1.0 && r > 0) {
    // Disoccluded (no history): a wider spatial pass over this frame's filtered values.
    PvSurface a = pv_surface_at(pv_source_pixel(q));
    float angle = 6.2831853 * float(gib_pcg(uint(q.x) * 7919u + uint(q.y) * 104729u + pv_frame()) >> 8) / 16777216.0;
    mat2 rot = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
    vec4 sy = y;
    vec2 sc = c.xy;
    float sw = 1.0;
    for (uint i = 0u; i < kPvPoissonTaps; ++i) {
      ivec2 q2 = q + ivec2(round(rot * kPoisson[i] * float(2 * r)));
      if (any(lessThan(q2, ivec2(0))) || any(greaterThanEqual(q2, size))) continue;
      PvSurface b = pv_surface_at(pv_source_pixel(q2));
      float w = pv_bilateral(a, b);
      if (w <= 0.0) continue;
      vec4 y2 = imageLoad(history_y, q2);  // Y0 for b's normal: re-evaluated for a's
      sy += w * vec4(pv_y_for_normal(y2.x, y2.yzw, a.normal, b.normal), y2.yzw);
      sc += w * imageLoad(history_c, q2).xy;
      sw += w;
    }
    y = sy / sw;
    c.xy = sc / sw;
  }
  imageStore(gi_y, q, y);
  imageStore(gi_c, q, c);
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(history_y);
  if (any(greaterThanEqual(q, size))) return;
  if (kKernel == kPvDenoiseFilter)
    filter_pixel(q, size);
  else
    poisson_pixel(q, size);
}
