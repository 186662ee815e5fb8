// LDR-FLIP and HDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating
// Images", HPG 2020; "Visualizing and Communicating Errors in Rendered Images", Ray Tracing
// Gems II, 2021), computed the way the reference tool (v1.6) does; see
// data/flip-vectors/NOTES.md for the pipeline and its constants. No image I/O here.
//
// Inputs are linear RGB FloatImages (channels 1-4: the first three are R, G, B; a 1- or
// 2-channel image is treated as grey from channel 0).
//  - LDR: linear RGB decoded from sRGB 8-bit (see srgb8_to_linear); values are clamped to
//    [0, 1] here as well, as the tool does after decoding.
//  - HDR: linear, unclamped floats (EXR-like). Each exposure is tone mapped and clamped.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "metrics/colormap.h"  // magma_error_map for FLIP error maps
#include "renderer/image/float_image.h"

namespace gib {

struct FlipOptions {
  // Pixels per degree of visual angle. Default: 0.7 m from a 0.7 m wide, 3840 px display
  // (3840 * pi / 180, as float32).
  double ppd = 67.02064514160156;
  enum class Mode { ldr, hdr } mode = Mode::ldr;
  std::string tonemapper = "aces";  // HDR only: aces | reinhard | hable
  // HDR only. Unset values are computed from the reference image as the tool does:
  // start = log2(x_max / L_max), stop = log2(x_max / L_median), where T(x_max) = 0.85;
  // num_exposures = max(2, ceil(stop - start)).
  std::optional<double> start_exposure, stop_exposure;
  std::optional<int> num_exposures;
};

struct FlipResult {
  FloatImage error_map;   // 1 channel, per-pixel FLIP in [0, 1]
  double mean = 0;        // arithmetic mean of error_map, summed in double
  // Weighted percentiles as the tool defines them: sort the values ascending, keep a
  // float32 running sum, report the first value at which it exceeds p * (float32 sum of
  // the map taken row-major); 0 when the map is all zero.
  double weighted_median = 0, weighted_q1 = 0, weighted_q3 = 0;
  double min = 0, max = 0;
  // HDR: the exposure range actually used. LDR: 0, 0 and 0.
  double start_exposure = 0, stop_exposure = 0;
  int num_exposures = 0;
  double ppd = 0;
};

// Throws std::invalid_argument on a size mismatch, an empty image, ppd <= 0, an unknown
// tone mapper, start > stop, or num_exposures < 1.
FlipResult flip(const FloatImage& reference, const FloatImage& test, const FlipOptions& options);

// Decodes 8-bit sRGB (3 bytes per pixel, row-major) to linear RGB as the tool does:
// /255, sRGB EOTF, clamp to [0, 1]. Returns a 3-channel image.
FloatImage srgb8_to_linear(const std::vector<uint8_t>& rgb, uint32_t width, uint32_t height);

// Pixels per degree from viewing conditions: distance and monitor width in metres.
double flip_ppd(double distance_m, double monitor_width_m, double monitor_width_px);

}  // namespace gib
