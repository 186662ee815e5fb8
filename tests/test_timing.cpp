// GPU times are taken on scan-free frames (perf/frame_timing.h): `gibench
// run`, `sweep` and `bench` time the same work the same way. No assertion here is on a time
// (project rule: speed is checked by benchmarks that print figures); the tests check structure:
// the timed frames had no scan dispatch, the timed work is the same in all three paths, and
// the timing frames change no evaluated image or scan result. The medians and their ratios
// are printed for reading.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include "gpu_fixture.h"
#include "harness/case.h"
#include "harness/case_render.h"
#include "harness/timing.h"
#include "perf/frame_timing.h"

namespace gib {
namespace {

const std::string kCases = std::string(GIB_SOURCE_DIR) + "/cases";

// cornell (direct) at a small size: 2 case frames, 3 timing frames.
Case small_cornell() {
  Case c = load_case(kCases + "/cornell.json");
  c.width = 48;
  c.height = 27;
  c.frames = 2;
  c.timing_frames = 3;
  return c;
}

std::vector<std::string> names(const FrameResult& f) {
  std::vector<std::string> n;
  for (auto& p : f.passes) n.push_back(p.name);
  return n;
}

std::vector<std::string> running(const Plan& plan) {
  std::vector<std::string> n;
  for (auto* p : plan.running()) n.push_back(p->name);
  return n;
}

class Timing : public test::GpuTest {};

TEST_F(Timing, RunSweepAndBenchTimeTheSameScanFreeWork) {
  const Case c = small_cornell();
  const TechniqueRun& run = c.techniques.front();
  ASSERT_EQ(run.technique, "direct");
  std::vector<TimingPath> paths = measure_timing(gpu(), c, run, "medium", 1);
  ASSERT_EQ(paths.size(), 3u);
  // The run path did scan its case frames (so "scan-free" below means the scan was switched off).
  EXPECT_GT(paths[0].scanned_dispatches, 0u);
  EXPECT_EQ(paths[1].scanned_dispatches, 0u);
  const std::string work = timed_work(paths[0].plan);
  EXPECT_FALSE(running(paths[0].plan).empty());
  for (auto& p : paths) {
    SCOPED_TRACE(p.name);
    ASSERT_EQ(p.repeats.size(), 1u);
    const perf::FrameTiming& t = p.repeats.front();
    EXPECT_EQ(t.source, "extra");
    EXPECT_EQ(t.frames.size(), c.timing_frames);
    EXPECT_EQ(t.warmup, c.frames);  // run and sweep: the case's frames; bench: as many warm-up frames
    EXPECT_EQ(t.scan_dispatches, 0u);
    EXPECT_TRUE(t.scan_free());
    for (auto& f : t.frames) {
      EXPECT_EQ(f.scan_dispatches, 0u);
      EXPECT_EQ(f.scan_ms, 0.0);
      EXPECT_EQ(names(f), running(p.plan));
    }
    EXPECT_EQ(timed_work(p.plan), work) << "the timed work differs from run's";
  }
  auto med = [&](size_t i) { return perf::median_of(paths[i].frame_ms()); };
  std::printf("timing (48x27 cornell direct, %u timed frames each): run %.4f ms, sweep %.4f ms, bench %.4f ms; "
              "run/sweep %.3f, run/bench %.3f, sweep/bench %.3f\n",
              c.timing_frames, med(0), med(1), med(2), med(0) / med(1), med(0) / med(2), med(1) / med(2));
}

// The timing frames come after every read: the image, the stability result and the case's own
// frame count are those of a render without them.
TEST_F(Timing, TimingFramesChangeNoEvaluatedResult) {
  Case with = small_cornell();
  Case without = with;
  without.timing_frames = 0;
  const TechniqueRun& run = with.techniques.front();
  CaseRender a = render_case(gpu(), with, run, "medium", 0, 0, /*scan=*/true);
  CaseRender b = render_case(gpu(), without, run, "medium", 0, 0, /*scan=*/true);
  ASSERT_EQ(a.image.width, b.image.width);
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  EXPECT_EQ(std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)), 0);
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.stability.frames, with.frames);  // scanned: the case's frames, not the timing frames
  EXPECT_EQ(b.stability.frames, with.frames);
  for (size_t k = 0; k < kStabilityCategoryCount; ++k)
    EXPECT_EQ(a.stability.total(StabilityCategory(k)), b.stability.total(StabilityCategory(k)));
  EXPECT_EQ(a.settings_hash, b.settings_hash);
  // With the timing frames: scan-free, after the case's frames. Without (timing_frames 0): the
  // case's frames after the first, scanned, and the row says so.
  EXPECT_EQ(a.timing.source, "extra");
  EXPECT_TRUE(a.timing.scan_free());
  EXPECT_EQ(a.timing.frames.size(), with.timing_frames);
  EXPECT_EQ(b.timing.source, "case frames");
  EXPECT_EQ(b.timing.frames.size(), with.frames - 1);
  EXPECT_FALSE(b.timing.scan_free());
}

}  // namespace
}  // namespace gib
