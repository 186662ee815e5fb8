// One ROI's error of a technique's renders over several seeds against the reference, split so
// that attribution bars can say what an oracle removes: linear HDR MSE = bias^2 + variance
// (exactly), and the signed and absolute energy ratio (a leak and a darkening can cancel in a
// mean: the absolute one shows both).
#pragma once
#include <vector>

#include "metrics/image_metrics.h"
#include "renderer/image/float_image.h"

namespace gib::attribution {

struct RoiError {
  // Mean over seeds of the ROI's linear HDR MSE (RGB, per channel) against the reference.
  double mse = 0;
  double bias2 = 0;     // the MSE of the seeds' mean image
  double variance = 0;  // per-pixel variance over the seeds (1/K), averaged: mse = bias2 + variance
  // Over the seeds' mean image, of Rec.709 luminance L: (sum L - sum L_ref) / sum L_ref and
  // sum |L - L_ref| / sum L_ref (0 when the reference's sum is 0).
  double signed_energy = 0, abs_energy = 0;
  std::vector<double> per_seed_mse;
};

// `seeds`: one render per seed, every one the reference's size (throws std::invalid_argument
// naming both sizes otherwise, or with no seeds).
RoiError roi_error(const std::vector<FloatImage>& seeds, const FloatImage& reference, const metrics::PixelRect& r);

}  // namespace gib::attribution
