// pixel_denoise: the per-pixel denoiser (AC Shadows RTGI, "Denoising" and "Challenges: noise";
// the seed's is NRD-like, MSD, not described further). On the YCoCg SH of hit_lighting:
// 1. filter: a (2r+1)^2 bilateral over ray pixels (same plane within 2% of the depth, normals
//    cos^8, and with material_mask the same material class, translucent or opaque, so that
//    translucent surfaces do not bleed onto opaque ones), each neighbour's Y0 re-evaluated for
//    the centre's normal; then a temporal blend with last frame's history at the reprojected ray
//    pixel (accepted when the view depth agrees within 5%), weight 1 / frames up to
//    history_max_frames -> pixel_history_y / pixel_history_c (persistent); beside it a fast
//    history of Y0 (up to fast_history_frames) -> pixel_history_fast. Anti-lag (NRD-style, as
//    the seed's denoiser is): the slow history is clamped to the fast one +- anti_lag_sigma
//    standard deviations of their difference, predicted from the two averages' weights and the
//    estimate's noise (the filter window's Y0 variance over its effective sample count, and its
//    mean over the last history_max_frames frames where that is larger), and a clamped pixel
//    keeps the fast history's frame count (CPU mirror: pixel_denoise_temporal.h);
// 2. poisson: pixels without history (disoccluded) get an extra 8-tap Poisson disc of radius
//    2r over the filtered values, the seed's extra pass -> pixel_gi_y / pixel_gi_c.
// Slots: read pixel_sh, gbuffer_position, gbuffer_normal, gbuffer_emissive; writes
// pixel_history_y, pixel_history_c (rgba32f), pixel_history_fast (rgba32f) (and reads last frame's),
// pixel_gi_y, pixel_gi_c (rgba32f).
// Limits: no variance-guided spatial weights, no firefly clamp, no vegetation-specific
// reprojection; the history is reprojected with the camera's motion only (static geometry); the
// anti-lag tests each pixel alone, so a slow change under heavy per-pixel noise is followed late.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_pixel_denoise_pass();
}
