// Stage 3 of `gibench run`, evaluation: the metrics a case's thresholds name, measured on a
// row's output against a comparison image, and one threshold checked against a value.
//
//   plan (plan.h) -> render + evaluate (evaluate.h) -> measure (this file) -> verdict (verdict.h)
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness/case.h"
#include "metrics/flip.h"
#include "renderer/graph/stability.h"
#include "renderer/image/float_image.h"

namespace gib {

struct CheckResult {
  std::string metric, against, roi;
  double value = 0;
  std::optional<double> max, min;
  bool pass = true;
  // Not evaluated: the metric needs what this run did not produce (scan_* under
  // --no-stability-scan). Neither passes nor fails the row; listed in its messages.
  bool skipped = false;
  std::string message;  // "flip vs reference 0.21 > max 0.15 (by 0.06)"
};

// What the per-run metrics read beyond one image: the convergence curve (ROI mean luminance
// per frame, conv_*) and the last frames (flicker).
struct MetricSeries {
  const std::vector<double>* curve = nullptr;
  const std::vector<FloatImage>* frames = nullptr;
  const StabilityReport* stability = nullptr;  // scan_* metrics
  const std::vector<double>* nan_pixels = nullptr;  // nan_frames / nan_last_frame / nan_max_pixels
};

// The metric named by a threshold, of `output` against `against` (may be empty for metrics
// that need none), inside roi (normalised; whole image when absent).
double compute_metric(const Case& c, const std::string& metric, const FloatImage& output, const FloatImage* against,
                      const Roi* roi, const MetricSeries& series = {});

// The convergence metrics of a curve m (one value per frame) towards target t, from the 1-based
// settle_frame on; see case.h for their definitions.
double convergence_metric(const std::string& metric, const std::vector<double>& m, double target,
                          uint32_t settle_frame);

// `value` against the threshold's bounds, with the message the row shows; `frame` (0: none) is
// named in it.
CheckResult check_value(const Threshold& t, double value, uint32_t frame);
// How far a value lies outside a threshold's bounds (<= 0 inside; NaN counts as infinitely far).
double violation(const Threshold& t, double v);

FlipOptions flip_options(const Case& c);
const Roi* find_roi(const Case& c, const std::string& name);
// The stability scan's case metrics, each the sum of its categories over every frame, pass and
// resource (compute_metric and the per-row scan_* metrics both read this).
const std::vector<std::pair<std::string, std::vector<StabilityCategory>>>& scan_metrics();

}  // namespace gib
