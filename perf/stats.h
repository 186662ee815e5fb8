// Statistics for pass timings: robust summaries, the Mann-Whitney U rank test with the
// Hodges-Lehmann estimate of the change and its distribution-free confidence interval, and
// the smallest regression a set of samples can detect. Pure CPU, no Vulkan.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace gib::perf {

struct Summary {
  size_t n = 0;
  double median = 0, q1 = 0, q3 = 0, min = 0, max = 0;
};
Summary summarize_samples(std::vector<double> samples);
double median_of(std::vector<double> v);
// Linear-interpolated quantile (type 7) of sorted values.
double quantile_sorted(const std::vector<double>& sorted, double q);

// Base vs new, compared on log(time) so the shift is a ratio: change = new / base - 1.
struct RankTest {
  size_t m = 0, n = 0;     // base and new sample counts
  double u = 0;            // pairs (base_i, new_j) with new_j > base_i (ties count 1/2)
  double p = 1;            // two-sided p-value of "same distribution"
  bool exact = false;      // exact null distribution (no ties, m and n <= 50) vs normal approx
  double change = 0;       // Hodges-Lehmann: exp(median of log(new_j) - log(base_i)) - 1
  double ci_low = 0, ci_high = 0;  // interval of `change` at `confidence`
  bool ci_valid = false;   // false: too few samples to reach the confidence at all
  double confidence = 0.95;
};
// Throws std::invalid_argument on empty inputs or non-positive / non-finite samples.
RankTest mann_whitney(const std::vector<double>& base, const std::vector<double>& next, double confidence = 0.95);

enum class Verdict { unchanged, regression, improvement, too_few_samples };
const char* verdict_name(Verdict v);
// Regression: the whole interval lies above 0 (outside noise at the test's confidence) and the
// estimate is at least `min_change` (a fraction, e.g. 0.02): drift smaller than that between
// two runs is not worth a red line even when it is statistically real.
Verdict judge(const RankTest& t, double min_change);

// The smallest slowdown s (fraction) for which comparing `samples` against samples * (1 + s)
// would be flagged by judge(mann_whitney(...), 0) at `confidence`: the noise floor of a run
// with this spread and this many samples. Infinity when too few samples.
double detectable_regression(const std::vector<double>& samples, double confidence = 0.95);

// Exact null distribution of U for sizes m, n: P(U <= u) for u = 0..m*n.
std::vector<double> mann_whitney_cdf(size_t m, size_t n);
double normal_quantile(double p);  // inverse standard normal CDF

}  // namespace gib::perf
