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
layout(push_constant) uniform Push { PvParams pv; vec4 anti_lag; };
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
layout(set = 0, binding = kPvDenoiseBindPrevFast, rgba32f) uniform readonly image2D prev_fast;
layout(set = 0, binding = kPvDenoiseBindFast, rgba32f) uniform writeonly image2D history_fast;
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

// The anti-lag: the slow history (this frame blended in, weight a_s = 1 / frames) is clamped
// to the fast one (weight a_f = 1 / n_fast, n_fast up to fast_history_frames) plus or minus
// `sigma` standard deviations of their difference where the estimate's noise cannot explain it.
// Two exponential averages of one estimate whose frames are independent with variance var_est
// differ with variance var_est x (a_s / (2 - a_s) + a_f / (2 - a_f) - 2 a_s a_f / (a_s + a_f -
// a_s a_f)) (0 when both weigh alike: then they are the same average). var_est is the larger of
// this frame's spatial estimate var_now (the window's variance over its effective sample count)
// and its mean over the last history_max_frames frames: few rays of a window see a small bright
// source (a sunlit patch through a window), so in most frames the window's sample variance is
// far below the true one and now and then far above it; unbiased frame by frame, its mean over
// frames holds the true variance, and as a spatial estimate it does not grow with a change of
// the light over time. A still scene then leaves the band in the share of pixels the normal
// tail gives (0.27% a frame at 3 sigma); a lighting change that moves the estimate beyond its
// noise is followed within the fast history's frames. Y0 (luminance) decides; Y1 and the
// chroma are scaled with it. A clamped history keeps the fast history's frame count.
float pv_anti_lag(float fast, float var_est, float n_fast, vec4 y_now, vec2 c_now, inout vec4 y, inout vec2 c,
                  float frames) {
  float a_s = 1.0 / frames, a_f = 1.0 / n_fast;
  float d2 = a_s / (2.0 - a_s) + a_f / (2.0 - a_f) - 2.0 * a_s * a_f / (a_s + a_f - a_s * a_f);
  float band = anti_lag.x * sqrt(var_est * max(d2, 0.0));
  float target = clamp(y.x, max(fast - band, 0.0), fast + band);
  if (target == y.x) return frames;
  if (y.x > 0.0) {
    c *= target / y.x;
    y *= target / y.x;
  } else if (y_now.x > 0.0) {
    y = y_now * (target / y_now.x);
    c = c_now * (target / y_now.x);
  } else {
    y = vec4(target, 0.0, 0.0, 0.0);
    c = vec2(0.0);
  }
  return min(frames, n_fast);
}

void filter_pixel(ivec2 q, ivec2 size) {
  PvSurface a = pv_surface_at(pv_source_pixel(q));
  if (a.depth == 0.0) {
    imageStore(history_y, q, vec4(0.0));
    imageStore(history_c, q, vec4(0.0));
    imageStore(history_fast, q, vec4(0.0));
    return;
  }
  int r = int(pv.flags.w & 0xffffu);
  vec4 sum_y = vec4(0.0);
  vec2 sum_c = vec2(0.0);
  float sum_w = 0.0, sum_w2 = 0.0, sum_wy2 = 0.0;
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
      sum_w2 += w * w;
      sum_wy2 += w * y.x * y.x;
    }
  vec4 y = sum_y / sum_w;
  vec2 c = sum_c / sum_w;
  // This frame's noise: the neighbours' weighted Y0 variance (unbiased for reliability weights)
  // over the effective sample count n_eff = (sum w)^2 / sum w^2 is the variance of the mean y.x.
  float n_eff = sum_w * sum_w / sum_w2;
  float var_now = n_eff > 1.0 ? max(sum_wy2 / sum_w - y.x * y.x, 0.0) / (n_eff - 1.0) : 0.0;
  bool anti_lag_on = anti_lag.x > 0.0 && n_eff >= kPvAntiLagMinSamples;
  // The fast history's Y0, var_now's mean over frames and its frame count.
  vec4 fast = vec4(y.x, var_now, 1.0, 0.0);
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
        vec4 pf = imageLoad(prev_fast, qp);
        float n_fast = min(hc.z + 1.0, anti_lag.y);
        fast.x = mix(pf.x, y.x, 1.0 / n_fast);
        fast.z = min(pf.z + 1.0, float(n_max));
        fast.y = mix(pf.y, var_now, 1.0 / fast.z);
        float var_est = max(var_now, fast.y);
        vec4 y_now = y;
        vec2 c_now = c;
        frames = min(hc.z + 1.0, float(n_max));
        y = mix(imageLoad(prev_y, qp), y_now, 1.0 / frames);
        c = mix(hc.xy, c_now, 1.0 / frames);
        if (anti_lag_on) frames = pv_anti_lag(fast.x, var_est, n_fast, y_now, c_now, y, c, frames);
      }
    }
  }
  if (pv_flag(kPvFlagNanGuards) && !(gib_finite(y) && gib_finite(c) && gib_finite(fast))) {
    y = vec4(0.0);
    c = vec2(0.0);
    fast = vec4(0.0);
    frames = 0.0;
  }
  imageStore(history_y, q, y);
  imageStore(history_c, q, vec4(c, frames, clip.w));
  imageStore(history_fast, q, fast);
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
