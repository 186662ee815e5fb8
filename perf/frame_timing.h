// The one timing definition of every command that reports GPU time (`gibench run`, `sweep`,
// `bench`; `gibench timing` compares them): frames rendered with the stability scan off, after
// warm-up frames in the same executor; a pass's time and the frame time are the medians over
// those frames (spread: min, max, quartiles). The scan's own dispatches are subtracted from
// FrameResult::total_ms, but its barriers and cache traffic between passes still slow the
// passes it follows, so no scanned frame is ever timed.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "perf/clock_probe.h"
#include "perf/stats.h"
#include "renderer/graph/executor.h"

namespace gib::perf {

struct FrameTiming {
  // Where the timed frames came from: "extra" (time_frames: rendered for timing only) or
  // "case frames" (frames rendered for their images, timed after the first; see
  // harness/case_render.cpp for when).
  std::string source;
  uint32_t warmup = 0;              // frames the executor ran before the first timed one
  std::vector<FrameResult> frames;  // the timed frames
  uint32_t scan_dispatches = 0;     // stability-scan dispatches in the timed frames
  ClockCheck clock;                 // GPU clock before/after the timed frames (clock_probe.h)
  bool scan_free() const { return !frames.empty() && scan_dispatches == 0; }
  std::vector<double> frame_ms() const;
  Summary frame() const;  // of FrameResult::total_ms
  // Per running pass, execution order (the passes of the first timed frame).
  std::vector<std::pair<std::string, Summary>> passes() const;
};

// Timed frames from frames already rendered: `frames` came after `warmup` others.
FrameTiming timing_of(std::vector<FrameResult> frames, uint32_t warmup, std::string source);

// Switches the executor's stability scan off, renders `warmup` untimed frames and then `frames`
// timed ones, and switches the scan back as it was. On a GPU the clock is probed right before
// and right after the timed frames (FrameTiming::clock, perf/clock_probe.h). Nothing is read back: any image or
// stability result wanted from the executor must be read before (the frames move history on).
FrameTiming time_frames(Executor& ex, uint32_t warmup, uint32_t frames);

}  // namespace gib::perf
