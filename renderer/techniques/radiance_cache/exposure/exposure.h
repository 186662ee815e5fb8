// exposure: the radiance-cache technique's pre-exposure (RadianceCacheSettings::pre_exposure).
// Before final_gather, two dispatches (per-workgroup partial sums, then one workgroup adding
// them in a fixed order) reduce, over the pixels p whose x and y are multiples of
// kExposureStride (4: 1/16 of the image), the Rec.709 luminance
//   Y(p) = max(Y(direct_light this frame at p), Y(final_color last frame at p))
// (last frame's term from the second frame on; a non-finite or negative luminance is 0) to the
// log-average of the lit pixels (Y > kExposureMinLuminance): A = 2^mean(log2 Y), and writes the
// persistent buffer `exposure` = {P_now, P_prev, A, lit pixel count, partials...} (floats,
// exposure_shared.h),
//   P_now = 1 / A clamped to [2^-20, 2^20]; 1 when nothing is lit or pre_exposure is 0,
//   P_prev = last frame's P_now (P_now on the first frame).
// No CPU readback: final_gather multiplies every sample's radiance by P_now before its RGBA16F
// SH projection, gi_upscale rescales its (pre-exposed) history by P_now / P_prev and divides its
// output by P_now. Both read the buffer, so the graph keeps this pass exactly when they run.
// Slots: reads direct_light, read_prev final_color; read_write exposure (persistent buffer).
// Cost: see renderer/techniques/radiance_cache/radiance_cache.md, 'Pre-exposure' (H100 figures).
#pragma once
#include <cstdint>
#include <memory>

#include "renderer/image/float_image.h"
#include "renderer/graph/pass.h"

namespace gib {

std::unique_ptr<Pass> make_exposure_pass();

// CPU mirror of exposure.comp (double accumulation, so it matches the GPU to float rounding).
struct PreExposure {
  float p_now = 1.0f, p_prev = 1.0f;
  float average_luminance = 0.0f;  // log-average of the lit pixels; 0 when none
  uint32_t lit_pixels = 0;
};
// direct: this frame's direct_light; prev_color: last frame's final_color, or nullptr on the
// first frame (then p_prev = p_now); stored_p_now: the buffer's P_now from last frame.
PreExposure compute_pre_exposure(const FloatImage& direct, const FloatImage* prev_color, float stored_p_now,
                                 bool enabled = true);

}  // namespace gib
