#include "metrics/image_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gib::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_image(const char* fn, const char* which, const FloatImage& img) {
  if (img.channels < 1 || img.channels > 4)
    throw std::invalid_argument(
        fmt::format("{}: {} image has {} channels, expected 1 to 4", fn, which, img.channels));
  if (img.width == 0 || img.height == 0)
    throw std::invalid_argument(
        fmt::format("{}: {} image is {}x{}, expected at least one pixel", fn, which, img.width, img.height));
  const size_t expected = img.pixel_count() * img.channels;
  if (img.pixels.size() != expected)
    throw std::invalid_argument(fmt::format("{}: {} image ({}x{}x{}) holds {} floats, expected {}", fn, which,
                                            img.width, img.height, img.channels, img.pixels.size(), expected));
}

void check_pair(const char* fn, const FloatImage& ref, const FloatImage& test) {
  check_image(fn, "ref", ref);
  check_image(fn, "test", test);
  if (ref.width != test.width || ref.height != test.height)
    throw std::invalid_argument(fmt::format("{}: image sizes differ: ref {}x{}, test {}x{}; expected equal", fn,
                                            ref.width, ref.height, test.width, test.height));
}

// Grey images (1 or 2 channels) read as R = G = B = channel 0; alpha is never read.
std::array<double, 3> rgb(const FloatImage& img, size_t pixel) {
  const float* p = img.pixels.data() + pixel * img.channels;
  if (img.channels >= 3) return {p[0], p[1], p[2]};
  return {p[0], p[0], p[0]};
}

// Grey is returned as is: the weights sum to 1 only up to rounding.
double luma(const FloatImage& img, size_t pixel) {
  const float* p = img.pixels.data() + pixel * img.channels;
  if (img.channels < 3) return p[0];
  return 0.2126 * double(p[0]) + 0.7152 * double(p[1]) + 0.0722 * double(p[2]);
}

// std::max drops a NaN depending on argument order; a metric must keep it.
double max_keep_nan(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return kNaN;
  return std::max(a, b);
}

double tonemap_value(double v) { return srgb_oetf(std::isnan(v) ? v : std::clamp(v, 0.0, 1.0)); }

// Mean over pixels and RGB of f(ref value, test value).
template <class F>
double mean_over_rgb(const FloatImage& ref, const FloatImage& test, F f) {
  double sum = 0.0;
  const size_t n = ref.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    const auto r = rgb(ref, i), t = rgb(test, i);
    for (int c = 0; c < 3; ++c) sum += f(r[c], t[c]);
  }
  return sum / (3.0 * double(n));
}

struct UV {
  double u, v, Y;
  bool valid;
};

UV uv_of(const std::array<double, 3>& c) {
  const double X = 0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2];
  const double Y = 0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2];
  const double Z = 0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2];
  const double d = X + 15.0 * Y + 3.0 * Z;
  // `d <= 0` is false for NaN: a NaN pixel stays valid so that it reaches the result.
  return {4.0 * X / d, 9.0 * Y / d, Y, !(d <= 0.0)};
}

}  // namespace

PixelRect roi_pixels(const Roi& roi, uint32_t width, uint32_t height) {
  const bool finite = std::isfinite(roi.x0) && std::isfinite(roi.y0) && std::isfinite(roi.x1) && std::isfinite(roi.y1);
  if (!finite || roi.x0 < 0.0 || roi.y0 < 0.0 || roi.x1 > 1.0 || roi.y1 > 1.0 || !(roi.x0 < roi.x1) ||
      !(roi.y0 < roi.y1))
    throw std::invalid_argument(fmt::format(
        "roi ({}, {}, {}, {}): expected finite normalised coordinates with 0 <= x0 < x1 <= 1 and 0 <= y0 < y1 <= 1",
        roi.x0, roi.y0, roi.x1, roi.y1));
  // Pixel i is inside when x0 <= (i + 0.5) / W < x1, i.e. i >= x0 W - 0.5 and i < x1 W - 0.5.
  auto first = [](double edge, uint32_t size) {
    const double i = std::ceil(edge * double(size) - 0.5);
    return uint32_t(std::clamp(i, 0.0, double(size)));
  };
  PixelRect r;
  r.x_begin = first(roi.x0, width);
  r.x_end = first(roi.x1, width);
  r.y_begin = first(roi.y0, height);
  r.y_end = first(roi.y1, height);
  if (r.x_end <= r.x_begin || r.y_end <= r.y_begin)
    throw std::invalid_argument(fmt::format("roi ({}, {}, {}, {}) covers no pixel centre of a {}x{} image", roi.x0,
                                            roi.y0, roi.x1, roi.y1, width, height));
  return r;
}

double luminance(const FloatImage& img, uint32_t x, uint32_t y) {
  return luma(img, size_t(y) * img.width + x);
}

double srgb_oetf(double x) {
  if (x <= 0.0031308) return 12.92 * x;
  return 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

FloatImage tonemap_srgb(const FloatImage& img) {
  check_image("tonemap_srgb", "input", img);
  FloatImage out = img;
  const uint32_t colour = img.channels >= 3 ? 3 : 1;
  const size_t n = img.pixel_count();
  for (size_t i = 0; i < n; ++i)
    for (uint32_t c = 0; c < colour; ++c) {
      float& v = out.pixels[i * img.channels + c];
      v = float(tonemap_value(v));
    }
  return out;
}

double psnr(const FloatImage& ref, const FloatImage& test) {
  check_pair("psnr", ref, test);
  const double mse = mean_over_rgb(ref, test, [](double r, double t) {
    const double e = tonemap_value(t) - tonemap_value(r);
    return e * e;
  });
  if (std::isnan(mse)) return kNaN;
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}

std::string psnr_description() {
  return "PSNR (dB) on tone-mapped sRGB: linear values clamped to [0,1] at exposure 1 (no tone curve), "
         "sRGB OETF, MSE over RGB, 10*log10(1/MSE); identical images give inf";
}

double relmse(const FloatImage& ref, const FloatImage& test, double eps) {
  check_pair("relmse", ref, test);
  if (!(eps > 0.0) || !std::isfinite(eps))
    throw std::invalid_argument(fmt::format("relmse: eps is {}, expected a finite value > 0", eps));
  return mean_over_rgb(ref, test, [eps](double r, double t) { return (t - r) * (t - r) / (r * r + eps); });
}

double roi_mean_luminance(const FloatImage& img, double x0, double y0, double x1, double y1) {
  return roi_mean_luminance(img, Roi{x0, y0, x1, y1});
}

double roi_mean_luminance(const FloatImage& img, const Roi& roi) {
  check_image("roi_mean_luminance", "input", img);
  const PixelRect r = roi_pixels(roi, img.width, img.height);
  double sum = 0.0;
  for (uint32_t y = r.y_begin; y < r.y_end; ++y)
    for (uint32_t x = r.x_begin; x < r.x_end; ++x) sum += luminance(img, x, y);
  return sum / double(r.pixel_count());
}

double max_abs_error(const FloatImage& ref, const FloatImage& test) {
  check_pair("max_abs_error", ref, test);
  double m = 0.0;
  const size_t n = ref.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    const auto r = rgb(ref, i), t = rgb(test, i);
    for (int c = 0; c < 3; ++c) m = max_keep_nan(m, std::abs(t[c] - r[c]));
  }
  return m;
}

double mean_abs_error(const FloatImage& ref, const FloatImage& test) {
  check_pair("mean_abs_error", ref, test);
  return mean_over_rgb(ref, test, [](double r, double t) { return std::abs(t - r); });
}

NonFinite count_non_finite(const FloatImage& img) {
  NonFinite n;
  for (float v : img.pixels) {
    if (std::isnan(v))
      ++n.nan;
    else if (std::isinf(v))
      ++n.inf;
    else if (v < 0.0f)
      ++n.negative;
  }
  return n;
}

ChromaticityShift chromaticity_shift(const FloatImage& ref, const FloatImage& test, const Roi& roi,
                                     double luminance_floor) {
  check_pair("chromaticity_shift", ref, test);
  if (std::isnan(luminance_floor))
    throw std::invalid_argument("chromaticity_shift: luminance_floor is NaN, expected a number");
  const PixelRect rect = roi_pixels(roi, ref.width, ref.height);
  ChromaticityShift s;
  double sum = 0.0;
  for (uint32_t y = rect.y_begin; y < rect.y_end; ++y)
    for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) {
      const size_t i = size_t(y) * ref.width + x;
      const UV a = uv_of(rgb(ref, i)), b = uv_of(rgb(test, i));
      // `<` rather than `!(>=)`: a NaN luminance is not skipped, it reaches the result.
      if (a.Y < luminance_floor || b.Y < luminance_floor || !a.valid || !b.valid) {
        ++s.skipped;
        continue;
      }
      const double d = std::hypot(b.u - a.u, b.v - a.v);
      s.max = max_keep_nan(s.max, d);
      sum += d;
      ++s.pixels;
    }
  if (s.pixels == 0)
    throw std::invalid_argument(fmt::format(
        "chromaticity_shift: all {} pixels of the ROI are below the luminance floor {} (in ref or test); "
        "expected at least one above it",
        rect.pixel_count(), luminance_floor));
  s.mean = sum / double(s.pixels);
  return s;
}

double max_chromaticity_shift(const FloatImage& ref, const FloatImage& test, const Roi& roi,
                              double luminance_floor) {
  return chromaticity_shift(ref, test, roi, luminance_floor).max;
}

double banding_index(const FloatImage& img, const Roi& roi, const BandingOptions& options) {
  check_image("banding_index", "input", img);
  if (options.channel < -1 || options.channel >= int(img.channels))
    throw std::invalid_argument(fmt::format(
        "banding_index: channel {} for a {}-channel image, expected -1 (luminance) or 0 to {}", options.channel,
        img.channels, img.channels - 1));
  const uint32_t w = options.window;
  if (w < 2)
    throw std::invalid_argument(fmt::format("banding_index: window is {}, expected at least 2 steps", w));
  const PixelRect rect = roi_pixels(roi, img.width, img.height);

  auto value = [&](uint32_t x, uint32_t y) -> double {
    if (options.channel < 0) return luminance(img, x, y);
    return img.at(x, y, uint32_t(options.channel));
  };

  const bool rows = options.axis != BandingAxis::columns;
  const bool cols = options.axis != BandingAxis::rows;
  // A line of n pixels has n - 1 steps; it needs at least one full run of w steps.
  const bool rows_ok = rows && rect.width() >= w + 1;
  const bool cols_ok = cols && rect.height() >= w + 1;
  if (!rows_ok && !cols_ok)
    throw std::invalid_argument(fmt::format(
        "banding_index: ROI is {}x{} pixels, expected at least {} (window + 1) along a measured axis",
        rect.width(), rect.height(), w + 1));

  double sum_a = 0.0, sum_e = 0.0;
  std::vector<double> line, steps;
  auto measure_line = [&]() {
    steps.resize(line.size() - 1);
    for (size_t i = 0; i + 1 < line.size(); ++i) steps[i] = line[i + 1] - line[i];
    // Direct sums per run rather than a sliding update: no drift, and a linear ramp gives
    // exactly equal |d| so its index is 0 up to rounding of the steps themselves.
    for (size_t s = 0; s + w <= steps.size(); ++s) {
      double abs_sum = 0.0, sq_sum = 0.0;
      for (size_t j = s; j < s + w; ++j) {
        abs_sum += std::abs(steps[j]);
        sq_sum += steps[j] * steps[j];
      }
      sum_a += abs_sum * abs_sum;
      sum_e += sq_sum;
    }
  };
  if (rows_ok)
    for (uint32_t y = rect.y_begin; y < rect.y_end; ++y) {
      line.clear();
      for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) line.push_back(value(x, y));
      measure_line();
    }
  if (cols_ok)
    for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) {
      line.clear();
      for (uint32_t y = rect.y_begin; y < rect.y_end; ++y) line.push_back(value(x, y));
      measure_line();
    }
  if (std::isnan(sum_a) || std::isnan(sum_e)) return kNaN;
  if (sum_e == 0.0) return 0.0;
  // Cauchy-Schwarz bounds the ratio to [1/w, 1]; clamp only rounding.
  return std::clamp(1.0 - sum_a / (double(w) * sum_e), 0.0, 1.0 - 1.0 / double(w));
}

double flicker(const std::vector<FloatImage>& frames, const Roi& roi, double mean_floor) {
  if (frames.size() < 2)
    throw std::invalid_argument(fmt::format("flicker: {} frames, expected at least 2", frames.size()));
  if (!(mean_floor > 0.0))
    throw std::invalid_argument(fmt::format("flicker: mean_floor is {}, expected a value > 0", mean_floor));
  for (size_t k = 0; k < frames.size(); ++k) {
    const std::string which = fmt::format("frame {}", k);
    check_image("flicker", which.c_str(), frames[k]);
    if (frames[k].width != frames[0].width || frames[k].height != frames[0].height)
      throw std::invalid_argument(fmt::format("flicker: frame {} is {}x{}, expected {}x{} like frame 0", k,
                                              frames[k].width, frames[k].height, frames[0].width,
                                              frames[0].height));
  }
  const PixelRect rect = roi_pixels(roi, frames[0].width, frames[0].height);
  const double n = double(frames.size());
  double sum = 0.0;
  size_t counted = 0;
  for (uint32_t y = rect.y_begin; y < rect.y_end; ++y)
    for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) {
      // Two passes over values shifted by frame 0's: no cancellation for the small variances
      // of a converged image, and identical frames give exactly 0.
      const double base = luminance(frames[0], x, y);
      double shift = 0.0;
      for (const FloatImage& f : frames) shift += luminance(f, x, y) - base;
      shift /= n;
      const double mean = base + shift;
      if (mean < mean_floor) continue;  // NaN is not skipped: it reaches the result
      double var = 0.0;
      for (const FloatImage& f : frames) {
        const double d = (luminance(f, x, y) - base) - shift;
        var += d * d;
      }
      sum += std::sqrt(var / n) / mean;
      ++counted;
    }
  if (counted == 0)
    throw std::invalid_argument(fmt::format(
        "flicker: all {} pixels of the ROI have mean luminance below the floor {}; expected at least one above it",
        rect.pixel_count(), mean_floor));
  return sum / double(counted);
}

}  // namespace gib::metrics

namespace gib::metrics {

std::vector<double> penumbra_profile(const FloatImage& img, const Roi& roi) {
  check_image("penumbra_profile", "input", img);
  const PixelRect r = roi_pixels(roi, img.width, img.height);
  std::vector<double> out(r.width(), 0.0);
  for (uint32_t x = r.x_begin; x < r.x_end; ++x) {
    double sum = 0;
    for (uint32_t y = r.y_begin; y < r.y_end; ++y) sum += luminance(img, x, y);
    out[x - r.x_begin] = sum / r.height();
  }
  return out;
}

double penumbra_width(const std::vector<double>& profile, const std::vector<double>& dark_from, double lo, double hi) {
  if (profile.size() < 2 || dark_from.size() != profile.size())
    throw std::invalid_argument(fmt::format("penumbra_width: profiles of {} and {} columns, expected equal and >= 2",
                                            profile.size(), dark_from.size()));
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    throw std::invalid_argument(fmt::format("penumbra_width: levels lo {} hi {}, expected finite with hi > lo", lo, hi));
  const size_t n = profile.size();
  // Start at dark_from's darkest column (the umbra), walk towards its brighter end.
  const size_t start = size_t(std::min_element(dark_from.begin(), dark_from.end()) - dark_from.begin());
  const bool rightwards = dark_from.back() >= dark_from.front();
  const size_t steps = rightwards ? n - start : start + 1;
  auto at = [&](size_t i) { return (profile[rightwards ? start + i : start - i] - lo) / (hi - lo); };
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  auto crossing = [&](double level) {
    for (size_t i = 0; i < steps; ++i) {
      const double v = at(i);
      if (std::isnan(v)) return nan;
      if (v >= level) return i == 0 ? 0.0 : double(i - 1) + (level - at(i - 1)) / (v - at(i - 1));
    }
    return inf;
  };
  // Not dark where the reference's umbra is (light leaked): no edge.
  if (std::isnan(at(0))) return nan;
  if (!(at(0) < 0.1)) return inf;
  const double a = crossing(0.1), b = crossing(0.9);
  if (std::isnan(a) || std::isnan(b)) return nan;
  if (std::isinf(a) || std::isinf(b)) return inf;
  return b - a;
}

double penumbra_width_error(const FloatImage& ref, const FloatImage& test, const Roi& roi) {
  check_pair("penumbra_width_error", ref, test);
  const std::vector<double> pr = penumbra_profile(ref, roi), pt = penumbra_profile(test, roi);
  const auto [lo, hi] = std::minmax_element(pr.begin(), pr.end());
  const double w_ref = penumbra_width(pr, pr, *lo, *hi);
  if (!(w_ref > 0) || !std::isfinite(w_ref))
    throw std::invalid_argument(fmt::format(
        "penumbra_width_error: the reference has no shadow edge across the ROI (width {}), expected one", w_ref));
  return std::abs(penumbra_width(pt, pr, *lo, *hi) - w_ref) / w_ref;
}

}  // namespace gib::metrics
