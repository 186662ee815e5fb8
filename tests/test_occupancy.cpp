// bench's occupancy term (perf/occupancy.h) on known answers, the profiles' resident threads,
// and the executor's dispatch profile (thread counts, indirect read-back, unchanged output).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "perf/occupancy.h"
#include "perf/pipeline_stats.h"
#include "perf/profiles.h"
#include "renderer/graph/executor.h"
#include "renderer/passes/direct_lighting/direct_lighting_shared.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using namespace perf;
using glsl::kDirectGroup;
using glsl::kRcShadeGroup;

// Nominal figures: H100 SXM (132 SMs x 128 lanes at 1.98 GHz, 2048 threads per SM) and Xbox
// Series S (20 CUs x 64 lanes at 1.565 GHz, 1024 threads per CU).
constexpr double kH100Flops = 2.0 * 132 * 128 * 1.98, kH100Resident = 132.0 * 2048;
constexpr double kSeriesSFlops = 2.0 * 20 * 64 * 1.565, kSeriesSResident = 20.0 * 1024;
constexpr double kFlopRatio = kH100Flops / kSeriesSFlops;

TEST(Occupancy, BelowOneWaveOnBothScalesByTheClockRatio) {
  for (double threads : {1.0, 64.0, 1098.0, 20480.0}) {
    const double f = occupancy_factor(threads, kH100Resident, kSeriesSResident);
    EXPECT_NEAR(kFlopRatio * f, 1.98 / 1.565, 1e-12) << threads;
  }
  // No threads at all (an indirect dispatch of 0 groups): the same limit.
  EXPECT_NEAR(kFlopRatio * occupancy_factor(0, kH100Resident, kSeriesSResident), 1.98 / 1.565, 1e-12);
}

TEST(Occupancy, FillingBothScalesByTheFlopRatio) {
  EXPECT_DOUBLE_EQ(occupancy_factor(kH100Resident, kH100Resident, kSeriesSResident), 1.0);
  EXPECT_DOUBLE_EQ(occupancy_factor(1440000, kH100Resident, kSeriesSResident), 1.0);
}

TEST(Occupancy, BetweenTheTwoScalesByTheDevicesFill) {
  // Fills the Series S (x3) but a fifth of the H100: the H100 ran at a fifth of its rate.
  const double t = kH100Resident / 5;
  EXPECT_NEAR(occupancy_factor(t, kH100Resident, kSeriesSResident), 0.2, 1e-12);
  EXPECT_NEAR(occupancy_fill(t, kH100Resident), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(occupancy_fill(t, kSeriesSResident), 1.0);
}

TEST(Occupancy, UnknownResidencyLeavesTheFlopRatio) {
  EXPECT_DOUBLE_EQ(occupancy_factor(1000, 0, kSeriesSResident), 1.0);
  EXPECT_DOUBLE_EQ(occupancy_factor(1000, kH100Resident, 0), 1.0);
}

TEST(Occupancy, PassFactorWeighsDispatchesByTheirTime) {
  // Half the time in a dispatch that fills both, half in one of 1098 threads.
  const std::vector<DispatchShare> d = {{0.5, 1e6}, {0.5, 1098}};
  EXPECT_NEAR(pass_occupancy_factor(d, kH100Resident, kSeriesSResident), 0.5 + 0.5 * kSeriesSResident / kH100Resident,
              1e-12);
  EXPECT_DOUBLE_EQ(pass_occupancy_factor({}, kH100Resident, kSeriesSResident), 1.0);
  // Through the scaling: 1 ms of compute, 2 ms of memory at a quarter of the bandwidth.
  DeviceThroughput dev{kH100Flops * 1e3, 1000};
  ConsoleProfile p;
  p.fp32_tflops = kSeriesSFlops;
  p.bandwidth_gbs = 250;
  PassSplit s{3.0, 2e9, 2.0, 1.0};
  const double occ = pass_occupancy_factor(d, kH100Resident, kSeriesSResident);
  EXPECT_NEAR(scale_to_profile(s, dev, p, occ), 2.0 * 4 + 1.0 * kFlopRatio * occ, 1e-9);
  EXPECT_NEAR(scale_to_profile(s, dev, p), 2.0 * 4 + 1.0 * kFlopRatio, 1e-9);
}

TEST(Occupancy, DispatchLatencyScalesByTheClockRatio) {
  // Two dispatches of a 0.06 ms pass, each filling both GPUs: without latency the FLOP ratio.
  const std::vector<DispatchShare> d = {{0.5, 1e6}, {0.5, 1e6}};
  EXPECT_DOUBLE_EQ(pass_occupancy_factor(d, kH100Resident, kSeriesSResident), 1.0);
  // With 0.005 ms of latency per dispatch, 0.005 / 0.03 of each scales as a dispatch that fills
  // neither (kSeriesSResident / kH100Resident), the rest as before.
  const double lat = 0.005 / 0.03, idle = kSeriesSResident / kH100Resident;
  EXPECT_NEAR(pass_occupancy_factor(d, kH100Resident, kSeriesSResident, 0.005, 0.06), lat * idle + (1 - lat), 1e-12);
  // A dispatch no longer than the latency is all latency: the clock ratio.
  EXPECT_NEAR(kFlopRatio * pass_occupancy_factor({{1.0, 1e6}}, kH100Resident, kSeriesSResident, 0.01, 0.004),
              1.98 / 1.565, 1e-12);
  // No latency calibrated, or no pass time: unchanged.
  EXPECT_DOUBLE_EQ(pass_occupancy_factor(d, kH100Resident, kSeriesSResident, 0.0, 0.06), 1.0);
  EXPECT_DOUBLE_EQ(pass_occupancy_factor(d, kH100Resident, kSeriesSResident, 0.005, 0.0), 1.0);
}

TEST(Occupancy, SharesAreMediansNormalised) {
  DispatchSamples s;
  s.frames = 3;
  s.ms = {{1, 3, 2}, {6, 6, 7}};
  s.threads = {{64, 64, 128}, {1e6, 1e6, 1e6}};
  std::string why;
  auto shares = dispatch_shares(s, why);
  ASSERT_EQ(shares.size(), 2u) << why;
  EXPECT_DOUBLE_EQ(shares[0].fraction, 0.25);
  EXPECT_DOUBLE_EQ(shares[1].fraction, 0.75);
  EXPECT_DOUBLE_EQ(shares[0].threads, 64);
  s.consistent = false;
  EXPECT_TRUE(dispatch_shares(s, why).empty());
  EXPECT_NE(why.find("different numbers"), std::string::npos);
  s.consistent = true;
  s.ms[1] = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_TRUE(dispatch_shares(s, why).empty());
  EXPECT_NE(why.find("not timed"), std::string::npos);
}

TEST(Occupancy, ProfilesCarryResidentThreads) {
  auto profiles = load_profiles(find_data_dir("") + "/console-profiles.json");
  for (const ConsoleProfile& p : profiles) EXPECT_GT(p.resident_threads, 0u) << p.name;
  for (const ConsoleProfile& p : profiles) {
    if (p.name == "xbox-series-s") {
      EXPECT_EQ(p.resident_threads, 20u * 1024);
    }
  }
  const std::string bad = R"({"profiles": {"x": {"fp32_tflops": 1, "bandwidth_gbs": 1, "resident_threads_per_cu": 1024,
                          "targets": {"resolution": [8, 8]}}}})";
  try {
    parse_profiles(bad, "p.json");
    ADD_FAILURE() << "no error";
  } catch (const PerfError& e) {
    EXPECT_NE(std::string(e.what()).find("p.json: /profiles/x/compute_units"), std::string::npos) << e.what();
  }
}

TEST(SpirvLocalSize, ReadsTheExecutionMode) {
  // Header, an OpCapability, then OpExecutionMode %4 LocalSize 8 4 2.
  const std::vector<uint32_t> words = {0x07230203, 0x10000, 0, 10, 0, (2u << 16) | 17u, 1, (6u << 16) | 16u, 4, 17, 8, 4, 2};
  EXPECT_EQ(spirv_local_size(words), (std::array<uint32_t, 3>{8, 4, 2}));
  EXPECT_EQ(spirv_local_size(std::span<const uint32_t>(words.data(), 7)), (std::array<uint32_t, 3>{0, 0, 0}));
  std::vector<uint32_t> not_spirv = words;
  not_spirv[0] = 0;
  EXPECT_EQ(spirv_local_size(not_spirv), (std::array<uint32_t, 3>{0, 0, 0}));
}

class DispatchProfile : public test::GpuTest {};

// One radiance-cache frame with the profile on: direct dispatches count groups x workgroup size,
// the shade's indirect dispatch reads its groups back (the cells it shaded, rounded up to
// groups), and the output is the same bits as without the profile.
TEST_F(DispatchProfile, ThreadCountsAndUnchangedOutput) {
  const Technique& t = find_technique("radiance-cache");
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/thin_wall_005.json");
  Settings s = apply_preset(t, "low", Settings{});
  s.width = 40;
  s.height = 24;
  Executor plain(gpu(), scene, s, make_passes(t), {t.output});
  Executor profiled(gpu(), scene, s, make_passes(t), {t.output});
  profiled.enable_dispatch_profile(true);
  FrameResult fr;
  for (int f = 0; f < 3; ++f) {
    plain.run_frame();
    fr = profiled.run_frame();
  }
  const FloatImage a = plain.read(t.output), b = profiled.read(t.output);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  bool saw_shade = false, saw_direct = false;
  for (const PassTiming& pt : fr.passes) {
    for (const DispatchTiming& d : pt.dispatches) {
      if (gpu().info().is_software())
        EXPECT_TRUE(std::isnan(d.ms)) << pt.name << ": a CPU device times no dispatch";
      else
        EXPECT_GE(d.ms, 0.0) << pt.name << ": a GPU times every dispatch";
    }
    if (pt.name == "direct_lighting") {
      ASSERT_EQ(pt.dispatches.size(), 1u);
      EXPECT_EQ(pt.dispatches[0].threads, uint64_t((40 + kDirectGroup - 1) / kDirectGroup) *
                                              ((24 + kDirectGroup - 1) / kDirectGroup) * kDirectGroup * kDirectGroup);
      saw_direct = true;
    }
    if (pt.name == "radiance_cache_shade") {
      ASSERT_EQ(pt.dispatches.size(), 1u);
      EXPECT_TRUE(pt.dispatches[0].indirect);
      const auto raw = profiled.read_buffer("rc_counters");
      glsl::RcCounters c;
      ASSERT_GE(raw.size(), sizeof(c));
      std::memcpy(&c, raw.data(), sizeof(c));
      EXPECT_GT(c.active_cells, 0u);
      EXPECT_EQ(pt.dispatches[0].threads, uint64_t((c.active_cells + kRcShadeGroup - 1) / kRcShadeGroup) * kRcShadeGroup);
      saw_shade = true;
    }
  }
  EXPECT_TRUE(saw_direct);
  EXPECT_TRUE(saw_shade);
}

}  // namespace
}  // namespace gib

namespace gib::perf {
namespace {

// A pipeline with what a driver might report (Pipeline::statistics).
class FakePipeline final : public Pipeline {
 public:
  FakePipeline(std::string name, std::vector<PipelineStatistic> stats) : name_(std::move(name)), stats_(std::move(stats)) {}
  const std::string& name() const override { return name_; }
  std::array<uint32_t, 3> local_size() const override { return {8, 8, 1}; }
  const std::vector<PipelineStatistic>& statistics() const override { return stats_; }

 private:
  std::string name_;
  std::vector<PipelineStatistic> stats_;
};

TEST(PipelineStatistics, LineAndJsonSayWhatTheDriverReported) {
  FakePipeline a("a.comp", {{"Compute", "Register Count", "", 96}, {"Compute", "Local Memory Size", "", 68719477088.0}});
  FakePipeline b("b.comp", {});  // not captured: no line, an empty list in the JSON
  FakePipeline c("c.comp", {{"pre", "Instructions", "", 12}, {"main", "Instructions", "", 340}, {"main", "Ratio", "", 0.125}});
  std::vector<const Pipeline*> ps;
  add_pipelines(ps, {&a, nullptr, &b, &a});
  add_pipelines(ps, {&c, &b});
  ASSERT_EQ(ps, (std::vector<const Pipeline*>{&a, &b, &c}));  // first use order, once each, no null
  EXPECT_EQ(pipeline_statistics_line(ps),
            "a.comp: Register Count 96, Local Memory Size 0x1000000160; "
            "c.comp: pre Instructions 12, main Instructions 340, main Ratio 0.125");
  EXPECT_EQ(pipeline_statistics_line({&b}), "");
  const nlohmann::json j = pipeline_statistics_json(ps);
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["name"], "a.comp");
  EXPECT_EQ(j[0]["statistics"][0]["name"], "Register Count");
  EXPECT_EQ(j[0]["statistics"][0]["value"].get<double>(), 96.0);
  EXPECT_EQ(j[0]["statistics"][1]["value"].get<double>(), 68719477088.0);  // raw in the JSON
  EXPECT_TRUE(j[1]["statistics"].empty());
  EXPECT_EQ(j[2]["statistics"][1]["executable"], "main");
}

// The dispatch profile names each dispatch's pipeline; a Gpu asked for pipeline statistics
// gives every compute pipeline the driver's figures where it supports them (NVIDIA: register
// count, shared and local memory), and none where it does not (lavapipe).
TEST(PipelineStatistics, ProfiledDispatchesCarryTheirPipeline) {
  auto gpu = Gpu::create({.device = "", .validate = false, .pipeline_statistics = true});
  const Technique& t = find_technique("radiance-cache");
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/thin_wall_005.json");
  Settings s = apply_preset(t, "low", Settings{});
  s.width = 40;
  s.height = 24;
  Executor ex(*gpu, scene, s, make_passes(t), {t.output});
  ex.enable_dispatch_profile(true);
  const FrameResult fr = ex.run_frame();
  bool saw_direct = false;
  for (const PassTiming& pt : fr.passes)
    for (const DispatchTiming& d : pt.dispatches) {
      ASSERT_NE(d.pipeline, nullptr) << pt.name;
      EXPECT_EQ(d.pipeline->statistics().empty(), !gpu->info().pipeline_statistics) << d.pipeline->name();
      if (pt.name == "direct_lighting") {
        EXPECT_EQ(d.pipeline->name(), "direct_lighting.comp");  // pass name = file stem
        saw_direct = true;
      }
    }
  EXPECT_TRUE(saw_direct);
  std::printf("pipeline statistics: %s\n", gpu->info().pipeline_statistics ? "captured" : "not supported by this device");
}

}  // namespace
}  // namespace gib::perf
