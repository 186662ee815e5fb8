// pixel_denoise <-> C++: bindings, group size, push constants.
#ifndef GIB_PIXEL_DENOISE_SHARED_H
#define GIB_PIXEL_DENOISE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvDenoiseGroup, 8)
GIB_CONST(uint, kPvDenoiseBindPosition, 8)
GIB_CONST(uint, kPvDenoiseBindNormal, 9)
GIB_CONST(uint, kPvDenoiseBindEmissive, 10)
GIB_CONST(uint, kPvDenoiseBindSh, 11)          // pixel_sh (rg32ui)
GIB_CONST(uint, kPvDenoiseBindPrevY, 12)       // last frame's pixel_history_y
GIB_CONST(uint, kPvDenoiseBindPrevC, 13)       // last frame's pixel_history_c
GIB_CONST(uint, kPvDenoiseBindHistoryY, 14)    // pixel_history_y: Y0, Y1 (rgba32f)
GIB_CONST(uint, kPvDenoiseBindHistoryC, 15)    // pixel_history_c: Co, Cg, frames, view depth
GIB_CONST(uint, kPvDenoiseBindGiY, 16)         // pixel_gi_y (the upscaler's input)
GIB_CONST(uint, kPvDenoiseBindGiC, 17)         // pixel_gi_c
GIB_CONST(uint, kPvDenoiseBindPrevFast, 18)    // last frame's pixel_history_fast
GIB_CONST(uint, kPvDenoiseBindFast, 19)        // pixel_history_fast: fast Y0, mean var_now, its frames
GIB_CONST(uint, kPvDenoiseSpecKernel, 0)
GIB_CONST(uint, kPvDenoiseFilter, 0)           // spatial + temporal -> history
GIB_CONST(uint, kPvDenoisePoisson, 1)          // disoccluded pixels: Poisson disc over the history
GIB_CONST(uint, kPvPoissonTaps, 8)
// The anti-lag needs a noise estimate from this many effective samples (n_eff = (sum w)^2 /
// sum w^2 of the spatial filter): the variance of n samples is known to sqrt(2 / (n - 1)), 53%
// at 8; fewer (r 0, silhouettes, thin features) leave the history unclamped.
GIB_CONST(float, kPvAntiLagMinSamples, 8.0)
struct PvDenoisePush {
  PvParams pv;
  // The anti-lag: x sigma (the clamp band in standard deviations of the slow - fast difference;
  // 0: off), y the fast history's n_max (zw unused).
  vec4 anti_lag;
};
GIB_SHARED_END
#endif
