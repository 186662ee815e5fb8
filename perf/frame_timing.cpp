#include "perf/frame_timing.h"

#include <optional>

namespace gib::perf {

std::vector<double> FrameTiming::frame_ms() const {
  std::vector<double> v;
  for (auto& f : frames) v.push_back(f.total_ms);
  return v;
}

Summary FrameTiming::frame() const { return summarize_samples(frame_ms()); }

std::vector<std::pair<std::string, Summary>> FrameTiming::passes() const {
  std::vector<std::pair<std::string, Summary>> out;
  if (frames.empty()) return out;
  for (auto& p : frames.front().passes) {
    std::vector<double> ms;
    for (auto& f : frames)
      for (auto& q : f.passes)
        if (q.name == p.name) ms.push_back(q.ms);
    out.emplace_back(p.name, summarize_samples(std::move(ms)));
  }
  return out;
}

FrameTiming timing_of(std::vector<FrameResult> frames, uint32_t warmup, std::string source) {
  FrameTiming t;
  t.source = std::move(source);
  t.warmup = warmup;
  for (auto& f : frames) t.scan_dispatches += f.scan_dispatches;
  t.frames = std::move(frames);
  return t;
}

FrameTiming time_frames(Executor& ex, uint32_t warmup, uint32_t frames) {
  const bool scan = ex.stability_scan_enabled();
  ex.enable_stability_scan(false);
  for (uint32_t i = 0; i < warmup; ++i) ex.run_frame();
  const uint32_t before = ex.frames_run();
  std::optional<ClockProbe> probe;
  ClockCheck clock;
  if (!ex.gpu().info().is_software()) clock.before_probe_ms = probe.emplace(ex.gpu()).probe();
  std::vector<FrameResult> timed;
  for (uint32_t i = 0; i < frames; ++i) timed.push_back(ex.run_frame());
  if (probe) {
    clock.after_probe_ms = probe->probe();
    clock.fastest_probe_ms = probe->fastest();
  }
  ex.enable_stability_scan(scan);
  FrameTiming t = timing_of(std::move(timed), before, "extra");
  t.clock = clock;
  return t;
}

}  // namespace gib::perf
