// The occupancy term of bench's scaling model (bench/README.md, "Occupancy").
//
// The FLOP split scales a pass's compute time by F_dev / F_profile: it assumes the pass keeps
// every lane of both GPUs as busy. A dispatch of T threads fills min(1, T / R) of a GPU whose
// compute units hold R threads resident at once; a dispatch that fills only part of the device
// runs at that part of its rate (its threads' dependent chains are not hidden by others). So one
// dispatch's compute time scales by
//
//     F_dev / F_profile x u_dev / u_profile,   u = min(1, T / R)
//
// which is the FLOP ratio when T fills both, and (F_dev / R_dev) / (F_profile / R_profile) when it
// fills neither: the clock ratio where both hold as many threads per lane (an H100 SM's 2048 per
// 128 lanes, an RDNA2 CU's 1024 per 64), whatever T. A pass's compute time is shared over its
// dispatches by their measured time (Executor::enable_dispatch_profile).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace gib::perf {

// u = min(1, threads / resident): the part of a device's resident thread slots a dispatch fills.
double occupancy_fill(double threads, double resident);

// u_dev / u_profile for one dispatch; R_profile / R_dev for a dispatch of no threads (the limit:
// a dispatch with nothing to do costs its latency, which scales as one that fills neither).
double occupancy_factor(double threads, double resident_dev, double resident_profile);

// One dispatch of a pass: its share of the pass's time and its threads.
struct DispatchShare {
  double fraction = 0;  // of the pass's measured time (the shares sum to 1)
  double threads = 0;
};

// Sum over the dispatches of fraction x occupancy_factor: what multiplies the FLOP ratio of the
// pass's compute time. 1 when there are no dispatches (a pass of copies or draws).
//
// Dispatch latency (latency_ms > 0, the device's calibrated cost of an empty dispatch behind a
// barrier; pass_ms the pass's measured time): every dispatch spends that long launching and
// draining whatever its size, time in which no thread works. That part of a dispatch,
// min(1, latency_ms / (fraction x pass_ms)), scales as a dispatch that fills neither GPU
// (occupancy_factor of 0 threads: the clock ratio), the rest by its threads' fill. Without it a
// pass of several short dispatches on a wide GPU had its launches scaled by the FLOP ratio, as if
// a console launched a dispatch 16x slower than an H100 because it has 1/16 of its lanes.
double pass_occupancy_factor(const std::vector<DispatchShare>& dispatches, double resident_dev, double resident_profile,
                             double latency_ms = 0, double pass_ms = 0);

// Per-dispatch samples (ms and threads from several profiled frames) folded into shares: the
// median ms and median threads of each dispatch, in record order. Empty when the frames do not
// agree on the number of dispatches or no dispatch was timed (why: the reason, for the report).
struct DispatchSamples {
  std::vector<std::vector<double>> ms, threads;  // [dispatch][frame]
  uint32_t frames = 0;
  bool consistent = true;
};
std::vector<DispatchShare> dispatch_shares(const DispatchSamples& s, std::string& why);

}  // namespace gib::perf
