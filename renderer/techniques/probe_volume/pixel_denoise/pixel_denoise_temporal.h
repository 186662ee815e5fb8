// CPU mirror of pixel_denoise's temporal step for one ray pixel's Y0 (pixel_denoise.comp,
// filter_pixel after the spatial filter, and pv_anti_lag): the slow history (weight 1 / frames,
// frames up to history_max_frames), the fast history (up to fast_history_frames) and the
// anti-lag that clamps the slow one to the fast one +- sigma standard deviations of their
// difference. The shader scales Y1 and the chroma with Y0; Y0 alone decides, so it alone is
// mirrored; it agrees with the shader to float rounding.
#pragma once
#include <algorithm>
#include <cmath>

namespace gib {

struct PvDenoiseHistory {
  float y0 = 0.0f;      // the slow history's Y0 (pixel_history_y.x)
  float frames = 0.0f;  // the slow history's frame count (pixel_history_c.z; 0: none)
  // pixel_history_fast: the fast history's Y0, the spatial noise estimate (var_now) averaged
  // over the last n_max frames, and its frame count.
  float fast = 0.0f, var_mean = 0.0f, var_frames = 0.0f;
};

struct PvDenoiseTemporal {
  float n_max = 16.0f;       // history_max_frames
  float sigma = 3.0f;        // anti_lag_sigma (0: off)
  float fast_frames = 4.0f;  // fast_history_frames
};

// The spatial filter's output for this frame: its Y0 and the variance of that mean from the
// window (var_now), and whether the window had enough effective samples (kPvAntiLagMinSamples).
struct PvDenoiseSpatial {
  float y0 = 0.0f;
  float var_now = 0.0f;
  bool noise_known = true;
};

inline float pv_mix(float a, float b, float t) { return a * (1.0f - t) + b * t; }

// Variance of the difference of two exponential averages (weights a_s, a_f) of one estimate
// whose frames are independent with variance 1 (pixel_denoise.comp, pv_anti_lag).
inline float pv_ema_difference_variance(float a_s, float a_f) {
  return a_s / (2.0f - a_s) + a_f / (2.0f - a_f) - 2.0f * a_s * a_f / (a_s + a_f - a_s * a_f);
}

// One frame: `prev` accepted by the reprojection (prev.frames > 0) or not.
inline PvDenoiseHistory pv_denoise_temporal(const PvDenoiseHistory& prev, const PvDenoiseSpatial& now,
                                            const PvDenoiseTemporal& t) {
  PvDenoiseHistory out{now.y0, 1.0f, now.y0, now.var_now, 1.0f};
  if (t.n_max <= 1.0f || prev.frames <= 0.0f) return out;
  const float n_fast = std::min(prev.frames + 1.0f, t.fast_frames);
  out.fast = pv_mix(prev.fast, now.y0, 1.0f / n_fast);
  out.var_frames = std::min(prev.var_frames + 1.0f, t.n_max);
  out.var_mean = pv_mix(prev.var_mean, now.var_now, 1.0f / out.var_frames);
  const float var_est = std::max(now.var_now, out.var_mean);
  out.frames = std::min(prev.frames + 1.0f, t.n_max);
  out.y0 = pv_mix(prev.y0, now.y0, 1.0f / out.frames);
  if (t.sigma > 0.0f && now.noise_known) {
    const float d2 = pv_ema_difference_variance(1.0f / out.frames, 1.0f / n_fast);
    const float band = t.sigma * std::sqrt(var_est * std::max(d2, 0.0f));
    const float target = std::clamp(out.y0, std::max(out.fast - band, 0.0f), out.fast + band);
    if (target != out.y0) {
      out.y0 = target;
      out.frames = std::min(out.frames, n_fast);
    }
  }
  return out;
}

}  // namespace gib
