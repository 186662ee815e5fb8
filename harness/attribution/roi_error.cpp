#include "harness/attribution/roi_error.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace gib::attribution {

RoiError roi_error(const std::vector<FloatImage>& seeds, const FloatImage& reference, const metrics::PixelRect& r) {
  if (seeds.empty()) throw std::invalid_argument("attribution: expected at least one seed's render, got none");
  for (const FloatImage& s : seeds)
    if (s.width != reference.width || s.height != reference.height || s.channels < 3 || reference.channels < 3)
      throw std::invalid_argument(fmt::format("attribution: expected renders of the reference's {}x{} (RGB), got {}x{}x{}",
                                              reference.width, reference.height, s.width, s.height, s.channels));
  const double k = double(seeds.size());
  const double values = double(r.pixel_count()) * 3.0;
  RoiError e;
  e.per_seed_mse.assign(seeds.size(), 0.0);
  double sum_l = 0, sum_ref_l = 0, sum_abs = 0;
  for (uint32_t y = r.y_begin; y < r.y_end; ++y)
    for (uint32_t x = r.x_begin; x < r.x_end; ++x) {
      double mean_rgb[3] = {0, 0, 0};
      for (uint32_t c = 0; c < 3; ++c) {
        const double ref = reference.at(x, y, c);
        double mean = 0;
        for (size_t s = 0; s < seeds.size(); ++s) {
          const double d = seeds[s].at(x, y, c) - ref;
          e.per_seed_mse[s] += d * d;
          mean += seeds[s].at(x, y, c);
        }
        mean /= k;
        double var = 0;
        for (const FloatImage& s : seeds) var += (s.at(x, y, c) - mean) * (s.at(x, y, c) - mean);
        e.variance += var / k;
        e.bias2 += (mean - ref) * (mean - ref);
        mean_rgb[c] = mean;
      }
      const double l = 0.2126 * mean_rgb[0] + 0.7152 * mean_rgb[1] + 0.0722 * mean_rgb[2];
      const double l_ref = metrics::luminance(reference, x, y);
      sum_l += l;
      sum_ref_l += l_ref;
      sum_abs += std::abs(l - l_ref);
    }
  for (double& m : e.per_seed_mse) m /= values;
  e.bias2 /= values;
  e.variance /= values;
  for (double m : e.per_seed_mse) e.mse += m / k;
  if (sum_ref_l > 0) {
    e.signed_energy = (sum_l - sum_ref_l) / sum_ref_l;
    e.abs_energy = sum_abs / sum_ref_l;
  }
  return e;
}

}  // namespace gib::attribution
