#include "perf/occupancy.h"

#include <algorithm>
#include <cmath>

#include "perf/stats.h"

namespace gib::perf {

double occupancy_fill(double threads, double resident) {
  if (!(resident > 0)) return 1;
  return std::clamp(threads / resident, 0.0, 1.0);
}

double occupancy_factor(double threads, double resident_dev, double resident_profile) {
  if (!(resident_dev > 0) || !(resident_profile > 0)) return 1;
  if (!(threads > 0)) return resident_profile / resident_dev;
  return occupancy_fill(threads, resident_dev) / occupancy_fill(threads, resident_profile);
}

double pass_occupancy_factor(const std::vector<DispatchShare>& dispatches, double resident_dev, double resident_profile,
                             double latency_ms, double pass_ms) {
  if (dispatches.empty()) return 1;
  const double idle = occupancy_factor(0, resident_dev, resident_profile);
  double f = 0, total = 0;
  for (const DispatchShare& d : dispatches) {
    const double ms = d.fraction * pass_ms;
    const double latency = latency_ms > 0 && ms > 0 ? std::min(1.0, latency_ms / ms) : 0.0;
    f += d.fraction * (latency * idle + (1 - latency) * occupancy_factor(d.threads, resident_dev, resident_profile));
    total += d.fraction;
  }
  return total > 0 ? f / total : 1;
}

std::vector<DispatchShare> dispatch_shares(const DispatchSamples& s, std::string& why) {
  if (!s.consistent) {
    why = "the profiled frames recorded different numbers of dispatches";
    return {};
  }
  if (s.ms.empty()) {
    why = "no compute dispatch";
    return {};
  }
  std::vector<DispatchShare> out;
  double total = 0;
  for (size_t i = 0; i < s.ms.size(); ++i) {
    std::vector<double> ms;
    for (double v : s.ms[i])
      if (std::isfinite(v)) ms.push_back(std::max(0.0, v));
    if (ms.empty()) {
      why = "a dispatch was not timed (past the profile's timestamp limit, or a CPU device)";
      return {};
    }
    DispatchShare d;
    d.fraction = median_of(ms);
    d.threads = s.threads[i].empty() ? 0 : median_of(s.threads[i]);
    total += d.fraction;
    out.push_back(d);
  }
  if (!(total > 0)) {
    why = "the dispatches' timestamps read 0";
    return {};
  }
  for (DispatchShare& d : out) d.fraction /= total;
  return out;
}

}  // namespace gib::perf
