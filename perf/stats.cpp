#include "perf/stats.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace gib::perf {

double quantile_sorted(const std::vector<double>& s, double q) {
  if (s.empty()) return 0;
  double pos = q * double(s.size() - 1);
  size_t i = size_t(std::floor(pos));
  if (i + 1 >= s.size()) return s.back();
  double f = pos - double(i);
  return s[i] * (1 - f) + s[i + 1] * f;
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return quantile_sorted(v, 0.5);
}

Summary summarize_samples(std::vector<double> v) {
  Summary s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.median = quantile_sorted(v, 0.5);
  s.q1 = quantile_sorted(v, 0.25);
  s.q3 = quantile_sorted(v, 0.75);
  s.min = v.front();
  s.max = v.back();
  return s;
}

double normal_quantile(double p) {
  // Bisection on the CDF: plenty fast for the handful of calls a report makes.
  double lo = -40, hi = 40;
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    double cdf = 0.5 * std::erfc(-mid / std::sqrt(2.0));
    (cdf < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> mann_whitney_cdf(size_t m, size_t n) {
  // P_{i,j}(u) = i/(i+j) P_{i-1,j}(u-j) + j/(i+j) P_{i,j-1}(u): the largest of the i+j values
  // is either a base sample (it beats all j new ones... seen from new: contributes 0) or a new
  // one (it beats all i base samples). Here U counts new > base, so a new maximum adds i.
  const size_t umax = m * n;
  std::vector<std::vector<double>> prev(n + 1, std::vector<double>(umax + 1, 0.0)), cur = prev;
  for (size_t j = 0; j <= n; ++j) prev[j][0] = 1.0;  // i = 0: U = 0
  for (size_t i = 1; i <= m; ++i) {
    cur[0].assign(umax + 1, 0.0);
    cur[0][0] = 1.0;  // j = 0: U = 0
    for (size_t j = 1; j <= n; ++j) {
      std::vector<double>& c = cur[j];
      c.assign(umax + 1, 0.0);
      double wb = double(i) / double(i + j), wn = double(j) / double(i + j);
      for (size_t u = 0; u <= i * j; ++u) {
        double v = wb * prev[j][u];                    // largest is a base sample
        if (u >= i) v += wn * cur[j - 1][u - i];        // largest is a new sample: beats i base
        c[u] = v;
      }
    }
    std::swap(prev, cur);
  }
  std::vector<double> cdf(umax + 1);
  double acc = 0;
  for (size_t u = 0; u <= umax; ++u) cdf[u] = std::min(1.0, acc += prev[n][u]);
  return cdf;
}

namespace {

void check_samples(const std::vector<double>& v, const char* what) {
  if (v.empty()) throw std::invalid_argument(fmt::format("rank test: expected {} samples, got none", what));
  for (double x : v)
    if (!(x > 0) || !std::isfinite(x))
      throw std::invalid_argument(fmt::format("rank test: expected positive finite {} times, got {}", what, x));
}

}  // namespace

RankTest mann_whitney(const std::vector<double>& base, const std::vector<double>& next, double confidence) {
  check_samples(base, "base");
  check_samples(next, "new");
  RankTest t;
  t.m = base.size();
  t.n = next.size();
  t.confidence = confidence;
  const double mn = double(t.m) * double(t.n);
  std::vector<double> d;
  d.reserve(t.m * t.n);
  double u = 0;
  for (double b : base)
    for (double x : next) {
      d.push_back(std::log(x) - std::log(b));
      u += x > b ? 1.0 : (x == b ? 0.5 : 0.0);
    }
  t.u = u;
  std::sort(d.begin(), d.end());
  t.change = std::exp(quantile_sorted(d, 0.5)) - 1;

  // Ties across the pooled sample: tie-corrected variance, and no exact distribution.
  std::map<double, size_t> counts;
  for (double b : base) ++counts[b];
  for (double x : next) ++counts[x];
  double tie_sum = 0;
  for (auto& [v, c] : counts) tie_sum += double(c) * double(c) * double(c) - double(c);
  const double N = double(t.m + t.n);
  const bool ties = tie_sum > 0;
  const double alpha = 1 - confidence;
  t.exact = !ties && t.m <= 50 && t.n <= 50;

  size_t k = 0;  // CI = [d_(k), d_(mn-k+1)], 1-based; 0: not reachable
  if (t.exact) {
    auto cdf = mann_whitney_cdf(t.m, t.n);
    size_t ui = size_t(std::llround(u));
    double lower = cdf[ui], upper = 1.0 - (ui ? cdf[ui - 1] : 0.0);
    t.p = std::min(1.0, 2 * std::min(lower, upper));
    // Largest k with P(U <= k - 1) <= alpha / 2.
    for (size_t kk = 1; kk <= t.m * t.n; ++kk) {
      if (cdf[kk - 1] <= alpha / 2 + 1e-12) k = kk;
      else break;
    }
  } else {
    double var = mn / 12.0 * ((N + 1) - tie_sum / (N * (N - 1)));
    double sd = std::sqrt(std::max(var, 0.0));
    if (sd > 0) {
      double diff = u - mn / 2;
      double z = (std::fabs(diff) - 0.5) / sd;  // continuity correction
      t.p = std::min(1.0, std::erfc(std::max(z, 0.0) / std::sqrt(2.0)));
      double kk = std::floor(mn / 2 - normal_quantile(1 - alpha / 2) * sd);
      k = kk >= 1 ? size_t(kk) : 0;
    } else {
      t.p = 1;
    }
  }
  if (k >= 1 && k <= t.m * t.n) {
    t.ci_valid = true;
    t.ci_low = std::exp(d[k - 1]) - 1;
    t.ci_high = std::exp(d[t.m * t.n - k]) - 1;
  } else {
    t.ci_low = std::exp(d.front()) - 1;
    t.ci_high = std::exp(d.back()) - 1;
  }
  return t;
}

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::unchanged: return "unchanged";
    case Verdict::regression: return "REGRESSION";
    case Verdict::improvement: return "improvement";
    case Verdict::too_few_samples: return "too few samples";
  }
  return "?";
}

Verdict judge(const RankTest& t, double min_change) {
  if (!t.ci_valid) return Verdict::too_few_samples;
  if (t.ci_low > 0 && t.change >= min_change) return Verdict::regression;
  if (t.ci_high < 0 && t.change <= -min_change) return Verdict::improvement;
  return Verdict::unchanged;
}

double detectable_regression(const std::vector<double>& x, double confidence) {
  if (x.size() < 2) return std::numeric_limits<double>::infinity();
  for (double v : x)
    if (!(v > 0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
  // Comparing x with y = x (1 + s): the pairwise log differences are those of x with itself
  // shifted by log(1 + s), so the interval's lower end is d0_(k) + log(1 + s), and the
  // slowdown is flagged once that is above 0.
  std::vector<double> d;
  d.reserve(x.size() * x.size());
  for (double a : x)
    for (double b : x) d.push_back(std::log(b) - std::log(a));
  std::sort(d.begin(), d.end());
  const size_t n = x.size();
  const double alpha = 1 - confidence;
  size_t k = 0;
  if (n <= 50) {
    auto cdf = mann_whitney_cdf(n, n);
    for (size_t kk = 1; kk <= n * n; ++kk) {
      if (cdf[kk - 1] <= alpha / 2 + 1e-12) k = kk;
      else break;
    }
  } else {
    double mn = double(n) * double(n);
    double sd = std::sqrt(mn * (2.0 * double(n) + 1) / 12.0);
    double kk = std::floor(mn / 2 - normal_quantile(1 - alpha / 2) * sd);
    k = kk >= 1 ? size_t(kk) : 0;
  }
  if (k == 0) return std::numeric_limits<double>::infinity();
  // Strictly above: the smallest s with d0_(k) + log(1 + s) > 0.
  return std::exp(-d[k - 1]) - 1;
}

}  // namespace gib::perf
