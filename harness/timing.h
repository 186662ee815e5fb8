// `gibench timing --case C [--technique T] [--preset P]`: one case x technique x preset timed
// the way each command times it, side by side:
//   run    render_case with the stability scan on during the case's frames (as `gibench run`)
//   sweep  render_case without the scan (as `gibench sweep`)
//   bench  a fresh executor at the case's settings, perf::time_frames (as `gibench bench`)
// All three report medians over scan-free frames after warm-up (perf/frame_timing.h). Prints
// each path's frame median with its spread, the ratios between paths, per-pass medians, and
// whether the timed work was the same (pass list, work counters, resource sizes). Exit 1 only
// when the timed work differs or a timed frame had a scan dispatch: never on timings.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "harness/case.h"
#include "harness/suite.h"
#include "perf/frame_timing.h"
#include "renderer/vk/gpu.h"

namespace gib {

struct TimingOptions {
  SuiteOptions suite;             // --case (one case), --cases-dir, --device, --validate
  std::string technique, preset;  // "": the case's first run, its first preset
  uint32_t repeats = 3;           // each path rendered this many times, interleaved
  uint32_t frames = 0;            // timed frames per repeat (0: the case's timing_frames)
  int bench_warmup = -1;          // bench's warm-up frames (-1: the case's frames, as run and sweep)
  std::string json;               // write every sample here
};

struct TimingPath {
  std::string name;                       // run | sweep | bench
  std::vector<perf::FrameTiming> repeats;
  Plan plan;
  uint64_t scanned_dispatches = 0;        // scan dispatches before the timed frames (run: > 0)
  std::vector<double> frame_ms() const;   // every timed frame of every repeat
  std::vector<double> repeat_medians() const;
  std::vector<std::pair<std::string, perf::Summary>> passes() const;  // pooled over repeats
  uint32_t scan_dispatches() const;       // in the timed frames: 0
};

// The work a plan does per frame, as text: running passes in order with their declared work
// counters and bytes written, then every resource with its size. Equal texts: the same work.
std::string timed_work(const Plan& plan);

std::vector<TimingPath> measure_timing(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                                       uint32_t repeats, int bench_warmup = -1);
int cmd_timing(const TimingOptions& o);

}  // namespace gib
