#include "harness/measure.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "metrics/image_metrics.h"

namespace gib {

FlipOptions flip_options(const Case& c) {
  FlipOptions f;
  f.ppd = c.ppd;
  f.mode = c.flip_mode == "ldr" ? FlipOptions::Mode::ldr : FlipOptions::Mode::hdr;
  return f;
}

const Roi* find_roi(const Case& c, const std::string& name) {
  for (auto& r : c.rois)
    if (r.name == name) return &r;
  return nullptr;
}

namespace {

// Mean of a 1-channel map inside a normalised box.
double roi_mean(const FloatImage& map, const Roi& r) {
  double sum = 0;
  size_t n = 0;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      float u = (x + 0.5f) / map.width, v = (y + 0.5f) / map.height;
      if (u >= r.x0 && u < r.x1 && v >= r.y0 && v < r.y1) {
        sum += map.at(x, y, 0);
        ++n;
      }
    }
  if (!n) throw CaseError(fmt::format("roi '{}' covers no pixel at {}x{}", r.name, map.width, map.height));
  return sum / double(n);
}

FloatImage crop(const FloatImage& img, const Roi* r) {
  if (!r) return img;
  uint32_t x0 = uint32_t(std::floor(r->x0 * img.width)), x1 = uint32_t(std::ceil(r->x1 * img.width));
  uint32_t y0 = uint32_t(std::floor(r->y0 * img.height)), y1 = uint32_t(std::ceil(r->y1 * img.height));
  x1 = std::min(x1, img.width);
  y1 = std::min(y1, img.height);
  FloatImage out(x1 - x0, y1 - y0, img.channels);
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x)
      for (uint32_t ch = 0; ch < img.channels; ++ch) out.at(x - x0, y - y0, ch) = img.at(x, y, ch);
  return out;
}

std::string fmt_value(double v) { return std::isinf(v) ? "inf" : fmt::format("{:.4g}", v); }


}  // namespace

const std::vector<std::pair<std::string, std::vector<StabilityCategory>>>& scan_metrics() {
  static const std::vector<std::pair<std::string, std::vector<StabilityCategory>>> m = {
      {"scan_nan", {StabilityCategory::nan}},
      {"scan_inf", {StabilityCategory::pos_inf, StabilityCategory::neg_inf}},
      {"scan_negative", {StabilityCategory::negative}},
      {"scan_above_max", {StabilityCategory::above_max}},
      {"scan_saturated", {StabilityCategory::saturated}}};
  return m;
}

double convergence_metric(const std::string& metric, const std::vector<double>& m, double target,
                          uint32_t settle_frame) {
  if (m.empty()) throw CaseError(fmt::format("metric '{}': no convergence curve was recorded", metric));
  if (!(target > 0)) throw CaseError(fmt::format("metric '{}': target must be > 0, got {}", metric, target));
  size_t from = std::min<size_t>(settle_frame ? settle_frame - 1 : 0, m.size() - 1);
  auto rel = [&](double v) { return std::abs(v - target) / target; };
  if (metric == "conv_error_final") return rel(m.back());
  if (metric == "conv_error_max") {
    double worst = 0;
    for (size_t i = from; i < m.size(); ++i) worst = std::isnan(m[i]) ? m[i] : std::max(worst, rel(m[i]));
    return worst;
  }
  size_t n = m.size() - from;
  if (metric == "conv_drift") {
    size_t k = std::max<size_t>(1, n / 10);
    double a = 0, b = 0;
    for (size_t i = 0; i < k; ++i) {
      a += m[from + i];
      b += m[m.size() - 1 - i];
    }
    return std::abs(b - a) / double(k) / target;
  }
  if (metric == "conv_oscillation") {
    // 5-frame trailing mean, so per-frame noise of a stochastic technique does not read as
    // oscillation; then the total variation beyond the net change.
    std::vector<double> smooth;
    for (size_t i = from; i < m.size(); ++i) {
      size_t lo = i >= from + 4 ? i - 4 : from;
      double sum = 0;
      for (size_t j = lo; j <= i; ++j) sum += m[j];
      smooth.push_back(sum / double(i - lo + 1));
    }
    double tv = 0;
    for (size_t i = 1; i < smooth.size(); ++i) tv += std::abs(smooth[i] - smooth[i - 1]);
    return (tv - std::abs(smooth.back() - smooth.front())) / target;
  }
  throw CaseError(fmt::format("unknown convergence metric '{}'", metric));
}

double compute_metric(const Case& c, const std::string& metric, const FloatImage& output, const FloatImage* against,
                      const Roi* roi, const MetricSeries& series) {
  auto need = [&]() -> const FloatImage& {
    if (!against) throw CaseError(fmt::format("{}: metric '{}' needs an image to compare against", c.file, metric));
    if (against->width != output.width || against->height != output.height)
      throw CaseError(fmt::format("{}: metric '{}': output {}x{} vs comparison image {}x{}", c.file, metric,
                                  output.width, output.height, against->width, against->height));
    return *against;
  };
  if (metric == "flip") {
    FlipResult f = flip(need(), output, flip_options(c));
    return roi ? roi_mean(f.error_map, *roi) : f.mean;
  }
  if (metric == "psnr") return metrics::psnr(crop(need(), roi), crop(output, roi));
  if (metric == "relmse") return metrics::relmse(crop(need(), roi), crop(output, roi));
  if (metric == "max_abs_error") return metrics::max_abs_error(crop(need(), roi), crop(output, roi));
  if (metric == "roi_mean") {
    Roi all{"", 0, 0, 1, 1};
    const Roi& r = roi ? *roi : all;
    return metrics::roi_mean_luminance(output, r.x0, r.y0, r.x1, r.y1);
  }
  if (metric == "roi_ratio") {
    Roi all{"", 0, 0, 1, 1};
    const Roi& r = roi ? *roi : all;
    double den = metrics::roi_mean_luminance(need(), r.x0, r.y0, r.x1, r.y1);
    return metrics::roi_mean_luminance(output, r.x0, r.y0, r.x1, r.y1) / std::max(den, 1e-30);
  }
  metrics::Roi mroi = roi ? metrics::Roi{roi->x0, roi->y0, roi->x1, roi->y1} : metrics::Roi{};
  if (metric == "uv_shift_max") return metrics::max_chromaticity_shift(need(), output, mroi);
  if (metric == "banding") return metrics::banding_index(output, mroi);
  if (metric == "penumbra_width_error") {
    if (!roi) throw CaseError(fmt::format("{}: metric 'penumbra_width_error' needs a roi (a band across the shadow edge)", c.file));
    return metrics::penumbra_width_error(need(), output, mroi);
  }
  if (metric == "banding_excess") return metrics::banding_index(output, mroi) - metrics::banding_index(need(), mroi);
  if (metric == "flicker") {
    if (!series.frames || series.frames->size() < 2)
      throw CaseError(fmt::format("{}: metric 'flicker' needs the last frames (flicker_frames >= 2)", c.file));
    return metrics::flicker(*series.frames, mroi);
  }
  if (metric.rfind("conv_", 0) == 0) {
    if (!series.curve || !c.convergence)
      throw CaseError(fmt::format("{}: metric '{}' needs a convergence curve (top-level \"convergence\")", c.file, metric));
    return convergence_metric(metric, *series.curve, c.convergence->target, c.convergence->settle_frame);
  }
  if (metric == "nan_frames" || metric == "nan_last_frame" || metric == "nan_max_pixels") {
    if (!series.nan_pixels)
      throw CaseError(fmt::format("{}: metric '{}' needs per-frame NaN counts (top-level \"track_nan\": true)", c.file,
                                  metric));
    double frames = 0, last = 0, most = 0;
    for (size_t i = 0; i < series.nan_pixels->size(); ++i) {
      double n = (*series.nan_pixels)[i];
      if (n > 0) {
        ++frames;
        last = double(i + 1);
      }
      most = std::max(most, n);
    }
    return metric == "nan_frames" ? frames : metric == "nan_last_frame" ? last : most;
  }
  if (metric.rfind("scan_", 0) == 0) {
    if (!series.stability)
      throw CaseError(fmt::format("{}: metric '{}' needs the stability scan (gibench run without --no-stability-scan)",
                                  c.file, metric));
    for (const auto& [name, categories] : scan_metrics())
      if (metric == name) {
        uint64_t n = 0;
        for (StabilityCategory cat : categories) n += series.stability->total(cat);
        return double(n);
      }
  }
  if (metric == "nan_count") return double(metrics::count_non_finite(crop(output, roi)).nan);
  if (metric == "inf_count") return double(metrics::count_non_finite(crop(output, roi)).inf);
  throw CaseError(fmt::format("{}: unknown metric '{}'", c.file, metric));
}

double violation(const Threshold& t, double v) {
  if (std::isnan(v)) return std::numeric_limits<double>::infinity();
  double out = -std::numeric_limits<double>::infinity();
  if (t.max) out = std::max(out, v - *t.max);
  if (t.min) out = std::max(out, *t.min - v);
  return out;
}

CheckResult check_value(const Threshold& t, double value, uint32_t frame) {
  CheckResult r;
  r.metric = t.metric;
  r.against = t.against;
  r.roi = t.roi;
  r.max = t.max;
  r.min = t.min;
  r.value = value;
  std::string what = fmt::format("{}{}{}{}", t.metric, t.against.empty() ? "" : " vs " + t.against,
                                 t.roi.empty() ? "" : " in " + t.roi, frame ? fmt::format(" at frame {}", frame) : "");
  if (std::isnan(r.value)) {
    r.pass = false;
    r.message = what + " is NaN";
  } else if (t.max && r.value > *t.max) {
    r.pass = false;
    r.message = fmt::format("{} {} > max {} (by {})", what, fmt_value(r.value), fmt_value(*t.max),
                            fmt_value(r.value - *t.max));
  } else if (t.min && r.value < *t.min) {
    r.pass = false;
    r.message = fmt::format("{} {} < min {} (by {})", what, fmt_value(r.value), fmt_value(*t.min),
                            fmt_value(*t.min - r.value));
  } else {
    r.message = fmt::format("{} {} ok", what, fmt_value(r.value));
  }
  return r;
}

}  // namespace gib
