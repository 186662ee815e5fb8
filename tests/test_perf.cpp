// Perf tooling: the rank test and its interval on synthetic samples with known answers, the
// noise-floor estimate, the console-scaling arithmetic, plan byte counts, and error messages of
// the profile / sample loaders. No timing here: timings belong in benchmarks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <functional>
#include <random>
#include <map>
#include <set>
#include <algorithm>
#include <cstdlib>
#include <optional>

#include "perf/calibration.h"
#include "perf/frame_timing.h"
#include "perf/clock_probe.h"
#include "perf/perf.h"
#include "perf/profiles.h"
#include "perf/project_files.h"
#include "perf/stats.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/temp_dir.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib::perf {
namespace {

std::string read_text_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<double> lognormal(uint32_t seed, size_t n, double median, double sigma) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> z(0, 1);
  std::vector<double> v;
  for (size_t i = 0; i < n; ++i) v.push_back(median * std::exp(sigma * z(rng)));
  return v;
}

// Evenly spread quantiles of a log-normal: the same "shape" at every n, no sampling luck.
std::vector<double> ideal(size_t n, double median, double sigma) {
  std::vector<double> v;
  for (size_t i = 0; i < n; ++i) v.push_back(median * std::exp(sigma * normal_quantile((i + 0.5) / double(n))));
  return v;
}

TEST(PerfStats, ExactNullDistributionMatchesCounting) {
  // m = n = 5: 252 equally likely orderings; U <= 2 in 1 + 1 + 2 of them.
  auto cdf = mann_whitney_cdf(5, 5);
  ASSERT_EQ(cdf.size(), 26u);
  EXPECT_NEAR(cdf[0], 1.0 / 252, 1e-12);
  EXPECT_NEAR(cdf[2], 4.0 / 252, 1e-12);
  EXPECT_NEAR(cdf[3], 7.0 / 252, 1e-12);
  EXPECT_NEAR(cdf[25], 1.0, 1e-12);
  for (size_t u = 0; u < 25; ++u) EXPECT_NEAR(cdf[u], 1.0 - cdf[24 - u], 1e-12) << u;  // symmetric
}

TEST(PerfStats, CompleteSeparationHasTheSmallestExactP) {
  std::vector<double> base{1, 2, 3, 4, 5}, next{6, 7, 8, 9, 10};
  RankTest t = mann_whitney(base, next);
  EXPECT_TRUE(t.exact);
  EXPECT_DOUBLE_EQ(t.u, 25);
  EXPECT_NEAR(t.p, 2.0 / 252, 1e-12);
  EXPECT_TRUE(t.ci_valid);
  EXPECT_GT(t.ci_low, 0);
}

TEST(PerfStats, IdenticalSamplesAreUnchanged) {
  auto a = lognormal(1, 20, 5.0, 0.05);
  RankTest t = mann_whitney(a, a);
  EXPECT_NEAR(t.change, 0, 1e-12);
  EXPECT_GT(t.p, 0.9);
  EXPECT_LT(t.ci_low, 0);
  EXPECT_GT(t.ci_high, 0);
  EXPECT_EQ(judge(t, 0.0), Verdict::unchanged);
}

TEST(PerfStats, SameDistributionIsRarelyFlagged) {
  // 200 comparisons of two independent draws from one distribution: at 95% about 2.5% should
  // come out as regressions by chance; far more means the test or its interval is wrong.
  int flagged = 0;
  for (uint32_t s = 0; s < 200; ++s) {
    RankTest t = mann_whitney(lognormal(2 * s + 10, 15, 3.0, 0.1), lognormal(2 * s + 11, 15, 3.0, 0.1));
    flagged += judge(t, 0.0) == Verdict::regression;
  }
  EXPECT_LE(flagged, 12);
}

TEST(PerfStats, TenPercentShiftWithLowNoiseIsFlagged) {
  auto base = lognormal(7, 10, 2.0, 0.01);
  auto next = lognormal(8, 10, 2.2, 0.01);
  RankTest t = mann_whitney(base, next);
  EXPECT_EQ(judge(t, 0.02), Verdict::regression);
  EXPECT_NEAR(t.change, 0.10, 0.02);
  EXPECT_LT(t.ci_low, 0.10);
  EXPECT_GT(t.ci_high, 0.10);
  // The same shift the other way is an improvement, not a regression.
  EXPECT_EQ(judge(mann_whitney(next, base), 0.02), Verdict::improvement);
  // Below min_change it is not worth flagging even though it is significant.
  EXPECT_EQ(judge(t, 0.2), Verdict::unchanged);
}

TEST(PerfStats, TooFewSamplesCannotReachTheConfidence) {
  // m = n = 3: the most extreme ordering has p = 2/20 = 0.1 > 0.05.
  RankTest t = mann_whitney({1, 1.01, 1.02}, {2, 2.01, 2.02});
  EXPECT_FALSE(t.ci_valid);
  EXPECT_EQ(judge(t, 0.0), Verdict::too_few_samples);
}

TEST(PerfStats, TiesUseTheNormalApproximation) {
  RankTest t = mann_whitney({1, 1, 1, 2, 2, 2, 2, 1}, {1, 2, 2, 2, 2, 2, 2, 2});
  EXPECT_FALSE(t.exact);
  EXPECT_GT(t.p, 0);
  EXPECT_LE(t.p, 1);
  EXPECT_THROW(mann_whitney({}, {1.0}), std::invalid_argument);
  EXPECT_THROW(mann_whitney({1.0, -1.0}, {1.0}), std::invalid_argument);
}

TEST(PerfStats, DetectableRegressionShrinksWithMoreSamples) {
  double prev = INFINITY;
  for (size_t n : {5, 10, 20, 40, 80}) {
    double d = detectable_regression(ideal(n, 1.0, 0.05));
    EXPECT_LT(d, prev) << n;
    EXPECT_GT(d, 0) << n;
    prev = d;
  }
  EXPECT_LT(prev, 0.03);  // 80 samples of 5% noise resolve a few percent
  EXPECT_TRUE(std::isinf(detectable_regression(ideal(3, 1.0, 0.05))));  // 3 vs 3 never reaches 95%
}

TEST(PerfStats, DetectableRegressionIsTheFlaggingThreshold) {
  auto x = ideal(12, 4.0, 0.04);
  double d = detectable_regression(x);
  auto scaled = [&](double s) {
    std::vector<double> y;
    for (double v : x) y.push_back(v * (1 + s));
    return y;
  };
  EXPECT_EQ(judge(mann_whitney(x, scaled(d * 1.01)), 0.0), Verdict::regression);
  EXPECT_NE(judge(mann_whitney(x, scaled(d * 0.99)), 0.0), Verdict::regression);
  // More noise, same n: a larger floor.
  EXPECT_GT(detectable_regression(ideal(12, 4.0, 0.08)), d);
}

TEST(PerfStats, SummaryQuantiles) {
  Summary s = summarize_samples({5, 1, 4, 2, 3});
  EXPECT_DOUBLE_EQ(s.median, 3);
  EXPECT_DOUBLE_EQ(s.q1, 2);
  EXPECT_DOUBLE_EQ(s.q3, 4);
  EXPECT_DOUBLE_EQ(s.min, 1);
  EXPECT_DOUBLE_EQ(s.max, 5);
}

TEST(PerfModel, SplitAndScaleOnKnownNumbers) {
  DeviceThroughput dev{10000, 1000};  // 10 TFLOP/s, 1000 GB/s
  PassSplit s = split_pass(3.0, 1e9, dev);  // 1 GB at 1000 GB/s = 1 ms of memory
  EXPECT_DOUBLE_EQ(s.memory_ms, 1.0);
  EXPECT_DOUBLE_EQ(s.compute_ms, 2.0);
  ConsoleProfile p;
  p.fp32_tflops = 5;       // half the FLOPs: compute x2
  p.bandwidth_gbs = 250;   // a quarter of the bandwidth: memory x4
  EXPECT_DOUBLE_EQ(scale_to_profile(s, dev, p), 1.0 * 4 + 2.0 * 2);
  // More bytes than the measured time allows at the calibrated rate: all memory, no compute.
  PassSplit c = split_pass(3.0, 5e9, dev);
  EXPECT_DOUBLE_EQ(c.memory_ms, 3.0);
  EXPECT_DOUBLE_EQ(c.compute_ms, 0.0);
  EXPECT_DOUBLE_EQ(scale_to_profile(c, dev, p), 12.0);
}

TEST(PerfModel, PassBytesFromThePlan) {
  std::vector<PassDecl> decls(2);
  decls[0].name = "a";
  decls[0].slots = {{"img", Access::write, {Format::rgba32_float, SizeRule::render}}};
  decls[1].name = "b";
  decls[1].slots = {{"img", Access::read, {}}, {"out", Access::write, {Format::rgba8_unorm, SizeRule::half}}};
  CompileOptions co;
  co.outputs = {"out"};
  co.render_width = 16;
  co.render_height = 8;
  Plan plan = compile(decls, co);
  auto running = plan.running();
  ASSERT_EQ(running.size(), 2u);
  PassBytes a = pass_bytes(plan, *running[0]), b = pass_bytes(plan, *running[1]);
  EXPECT_EQ(a.read, 0u);
  EXPECT_EQ(a.written, 16u * 8 * 16);
  EXPECT_EQ(b.read, 16u * 8 * 16);
  EXPECT_EQ(b.written, 8u * 4 * 4);
}

// Sparse slots (Slot::touched) count the bytes their measured work moves: a scattered element
// moves a 32-byte sector, an appended one its own size, never more than the buffer; a
// read_write slot counts them as read and as written; without the counters (or with one
// missing) the buffer's size, and the slot is named as unresolved.
TEST(PerfModel, SparseSlotsCountTheBytesTheirWorkMoves) {
  Touched cells{1000, {{"collisions", 1}, {"queued", 2}}, 16, false};
  const std::map<std::string, double> counters = {{"collisions", 10}, {"queued", 5}};
  ASSERT_TRUE(touched_elements(cells, counters).has_value());
  EXPECT_DOUBLE_EQ(*touched_elements(cells, counters), 1000 + 10 + 2 * 5);
  EXPECT_FALSE(touched_elements(cells, {{"collisions", 10}}).has_value());
  EXPECT_EQ(touched_bytes(cells, 1020, 1u << 20), 1020u * 32);        // 16-byte cells: a sector each
  EXPECT_EQ(touched_bytes(cells, 1e9, 1u << 20), uint64_t(1) << 20);  // never more than the buffer
  Touched list{0, {{"queued", 1}}, 4, true};
  EXPECT_EQ(touched_bytes(list, 5, 1u << 20), 20u);  // appended: 4 bytes each
  Touched big{0, {}, 48, false};
  EXPECT_EQ(touched_bytes(big, 2, 1u << 20), 96u);  // elements larger than a sector: their size

  std::vector<PassDecl> decls(2);
  decls[0].name = "make";
  ResourceDesc table{Format::buffer, SizeRule::buffer};
  table.bytes = 1u << 20;
  ResourceDesc list_desc{Format::buffer, SizeRule::buffer};
  list_desc.bytes = 4096;
  decls[0].slots = {{"table", Access::write, table}, {"list", Access::write, list_desc}};
  decls[1].name = "update";
  decls[1].slots = {{"table", Access::read_write, {}, cells}, {"list", Access::read, {}, list}};
  decls[1].side_effect = true;
  CompileOptions co;
  Plan plan = compile(decls, co);
  auto running = plan.running();
  ASSERT_EQ(running.size(), 2u);
  const PassBytes before = pass_bytes(plan, *running[1]);
  EXPECT_EQ(before.read, (1u << 20) + 4096u);
  EXPECT_EQ(before.written, 1u << 20);
  EXPECT_EQ(before.unresolved, (std::vector<std::string>{"table", "list"}));
  const PassBytes after = pass_bytes(plan, *running[1], &counters);
  EXPECT_EQ(after.read, 1020u * 32 + 5u * 4);
  EXPECT_EQ(after.written, 1020u * 32);
  EXPECT_TRUE(after.unresolved.empty());
  EXPECT_EQ(after.sparse.size(), 2u);
  const std::map<std::string, double> partial = {{"queued", 5}};
  const PassBytes half = pass_bytes(plan, *running[1], &partial);
  EXPECT_EQ(half.read, (1u << 20) + 5u * 4);
  EXPECT_EQ(half.unresolved, std::vector<std::string>{"table"});
}

TEST(PerfModel, ScaleParsing) {
  EXPECT_DOUBLE_EQ(parse_scale("1/8"), 0.125);
  EXPECT_DOUBLE_EQ(parse_scale("0.25"), 0.25);
  EXPECT_DOUBLE_EQ(parse_scale("1"), 1.0);
  EXPECT_THROW(parse_scale("2"), PerfError);
  EXPECT_THROW(parse_scale("1/0"), PerfError);
  EXPECT_THROW(parse_scale("abc"), PerfError);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const PerfError& e) {
    return e.what();
  }
  return "";
}

TEST(PerfModel, RasterScalesByFillRate) {
  DeviceThroughput dev{10000, 1000, 20};  // 20 Gpixel/s
  ConsoleProfile p;
  p.fill_gpix = 64 * 2.23;  // PS5: 64 ROPs at 2.23 GHz
  EXPECT_DOUBLE_EQ(*scale_raster_to_profile(1.0, dev, p), 20.0 / (64 * 2.23));
  p.fill_gpix = 0;  // no ROP figure: no raster scaling
  EXPECT_FALSE(scale_raster_to_profile(1.0, dev, p).has_value());
  dev.fill_gpix = 0;  // not calibrated
  p.fill_gpix = 10;
  EXPECT_FALSE(scale_raster_to_profile(1.0, dev, p).has_value());
}

TEST(PerfProfiles, ErrorsNameTheFileAndField) {
  const std::string ok_profile =
      R"("fp32_tflops": 4.0, "bandwidth_gbs": 224.0, "targets": {"resolution": [1600, 900]})";
  auto one = [&](const std::string& body) { return R"({"profiles": {"xss": {)" + body + "}}}"; };
  EXPECT_EQ(parse_profiles(one(ok_profile), "p.json").at(0).width, 1600u);

  std::string e = error_of([&] { parse_profiles(one(R"("fp32_tflops": 4, "targets": {"resolution": [1, 1]})"), "p.json"); });
  EXPECT_NE(e.find("p.json"), std::string::npos) << e;
  EXPECT_NE(e.find("/profiles/xss/bandwidth_gbs"), std::string::npos) << e;

  e = error_of([&] { parse_profiles(one(R"("fp32_tflops": "fast", "bandwidth_gbs": 1, "targets": {"resolution": [1, 1]})"), "p.json"); });
  EXPECT_NE(e.find("/profiles/xss/fp32_tflops: expected a positive number"), std::string::npos) << e;

  EXPECT_DOUBLE_EQ(parse_profiles(one(ok_profile + R"(, "rops": 32, "clock_ghz": 1.565)"), "p.json").at(0).fill_gpix, 32 * 1.565);
  EXPECT_EQ(parse_profiles(one(ok_profile), "p.json").at(0).fill_gpix, 0.0);
  e = error_of([&] { parse_profiles(one(ok_profile + R"(, "rops": 32)"), "p.json"); });
  EXPECT_NE(e.find("/profiles/xss/clock_ghz: expected the clock"), std::string::npos) << e;
  e = error_of([&] { parse_profiles(one(ok_profile + R"(, "rops": -4, "clock_ghz": 1)"), "p.json"); });
  EXPECT_NE(e.find("/profiles/xss/rops: expected a positive integer"), std::string::npos) << e;

  e = error_of([&] { parse_profiles(one(R"("fp32_tflops": 1, "bandwidth_gbs": 1, "targets": {"resolution": [1600]})"), "q.json"); });
  EXPECT_NE(e.find("q.json: /profiles/xss/targets/resolution"), std::string::npos) << e;

  e = error_of([&] { parse_profiles("{\"profiles\": ", "broken.json"); });
  EXPECT_NE(e.find("broken.json"), std::string::npos) << e;
  EXPECT_NE(e.find("parse error"), std::string::npos) << e;

  e = error_of([&] { load_profiles("/nonexistent/profiles.json"); });
  EXPECT_NE(e.find("/nonexistent/profiles.json"), std::string::npos) << e;

  e = error_of([&] { select_profiles(parse_profiles(one(ok_profile), "p.json"), "ps9"); });
  EXPECT_NE(e.find("xss"), std::string::npos) << e;
  EXPECT_NE(e.find("ps9"), std::string::npos) << e;

  e = error_of([&] {
    parse_seed_tables(R"({"idtech8_gi_hotspot": {"platforms": {"ps5": {"resolution": [2560, 1440], "upscale": "slow"}}}})",
                      "s.json");
  });
  EXPECT_NE(e.find("s.json: /idtech8_gi_hotspot/platforms/ps5/upscale"), std::string::npos) << e;
  const std::string idtech = R"("idtech8_gi_hotspot": {"platforms": {"ps5": {"resolution": [2560, 1440], "upscale": 0.7}}})";
  e = error_of([&] { parse_seed_tables("{" + idtech + "}", "s.json"); });
  EXPECT_NE(e.find("s.json: /doom_visibility_buffer: expected the DOOM visibility buffer table"), std::string::npos) << e;
  e = error_of([&] { parse_alpha_cost_table(R"({"ac_shadows_alpha_test_cost": {"any_hit_limit_2": 0.85}})", "s.json"); });
  EXPECT_NE(e.find("s.json: /ac_shadows_alpha_test_cost/any_hit_limit_4: expected a positive number, got nothing"),
            std::string::npos)
      << e;
  e = error_of([&] {
    parse_seed_tables("{" + idtech + R"(, "doom_visibility_buffer": {"siege_scene_xbox_series_x_1440p_ms":
        {"deferred_texturing": {"no_vrcs": 4.2}}}})", "s.json");
  });
  EXPECT_NE(e.find("s.json: /doom_visibility_buffer/siege_scene_xbox_series_x_1440p_ms/deferred_texturing/vrcs: expected "
                   "milliseconds, got nothing"),
            std::string::npos)
      << e;
  // The AC Shadows tables: missing, and a non-number row.
  const std::string doom = R"("doom_visibility_buffer": {"siege_scene_xbox_series_x_1440p_ms": {"gbuffer_update": 0.2}})";
  e = error_of([&] { parse_seed_tables("{" + idtech + ", " + doom + "}", "s.json"); });
  EXPECT_NE(e.find("s.json: /ac_shadows_probe_update: expected an AC Shadows timing table"), std::string::npos) << e;
  e = error_of([&] {
    parse_seed_tables("{" + idtech + ", " + doom +
                          R"(, "ac_shadows_probe_update": {"platforms": {"ps5": {"probes_per_frame": 1024, "gbuffer_update": "fast"}}}})",
                      "s.json");
  });
  EXPECT_NE(e.find("s.json: /ac_shadows_probe_update/platforms/ps5/gbuffer_update: expected milliseconds"), std::string::npos)
      << e;
}

// The repository ships its own data/ (console profiles, seed timings): a missing or unreadable
// file there is a failure, not a skip.
TEST(PerfProfiles, RepoDataLoads) {
  const std::string dir = std::string(GIB_SOURCE_DIR) + "/data";
  for (const char* f : {"console-profiles.json", "seed-timings.json"})
    ASSERT_TRUE(std::filesystem::exists(dir + "/" + f)) << dir << "/" << f << " is missing";
  EXPECT_EQ(find_data_dir(dir), dir);
  auto profiles = load_profiles(dir + "/console-profiles.json");
  ASSERT_GE(profiles.size(), 1u);
  auto ps5 = select_profiles(profiles, "ps5");
  EXPECT_EQ(ps5.at(0).width, 2560u);
  const std::vector<SeedTable> seeds = load_seed_tables(dir + "/seed-timings.json");
  ASSERT_EQ(seeds.size(), 5u);
  const SeedTable& idtech = seeds[0];
  ASSERT_NE(idtech.find("ps5"), nullptr);
  EXPECT_GT(idtech.find("ps5")->ms.at("final_gather"), 0);
  for (const SeedTable& t : seeds) {
    // Each table belongs to a technique we have, and every pass it maps is one of that
    // technique's passes and names a row the table has (in every column but where a pass runs
    // only in one: the VRCS rate).
    const Technique& tech = find_technique(t.technique);
    for (auto& [pass, row] : t.pass_row) {
      EXPECT_TRUE(std::any_of(tech.passes.begin(), tech.passes.end(), [&](auto& e) { return e.name == pass; }))
          << t.name << ": " << pass << " is not a pass of " << t.technique;
      bool somewhere = false;
      for (auto& p : t.platforms) somewhere |= p.ms.count(row) > 0;
      EXPECT_TRUE(somewhere) << t.name << ": " << pass << " -> " << row;
    }
    // Its total row is the sum of the rows our passes map to where the seed's table says so
    // (DOOM: "Overall (no async)" = the sum of its rows).
    if (t.name == "doom_visibility_buffer")
      for (auto& p : t.platforms) {
        double sum = 0;
        std::set<std::string> rows;
        for (auto& [pass, row] : t.pass_row) rows.insert(row);
        for (auto& row : rows) sum += p.ms.count(row) ? p.ms.at(row) : 0.0;
        EXPECT_NEAR(sum, p.ms.at(t.total_row), 1e-9) << p.column;
      }
  }
  // AC Shadows' probe update (per probe: compared at 2560x1440, the budget is not a row) and
  // diffuse GI (its own resolution per platform) tables, both for probe-volume.
  const SeedTable& probes = seeds[2];
  EXPECT_EQ(probes.name, "ac_shadows_probe_update");
  EXPECT_EQ(probes.technique, "probe-volume");
  ASSERT_NE(probes.find("ps5"), nullptr);
  EXPECT_DOUBLE_EQ(probes.find("ps5")->ms.at("gbuffer_update"), 0.35);
  EXPECT_DOUBLE_EQ(probes.find("ps5")->ms.at("total"), 1.24);
  EXPECT_EQ(probes.find("ps5")->ms.count("probes_per_frame"), 0u);
  EXPECT_EQ(probes.find("ps5")->width, 2560u);
  const SeedTable& diffuse = seeds[3];
  EXPECT_EQ(diffuse.name, "ac_shadows_diffuse_gi");
  ASSERT_NE(diffuse.find("xbox-series-s"), nullptr);
  EXPECT_EQ(diffuse.find("xbox-series-s")->height, 900u);
  EXPECT_DOUBLE_EQ(diffuse.find("ps5")->ms.at("total"), 7.12);
  // AC Shadows' alpha table, keyed by our option values.
  const AlphaCostTable alpha = load_alpha_cost_table(dir + "/seed-timings.json");
  ASSERT_EQ(alpha.relative.size(), 5u);
  EXPECT_DOUBLE_EQ(alpha.relative.at({0, 2}).second, 0.85);
  EXPECT_DOUBLE_EQ(alpha.relative.at({2, 0}).second, 0.6);
  EXPECT_EQ(alpha.relative.at({1, 2}).first, "dither_plus_any_hit_limit_2");
  // DOOM's table: a column per VRCS setting, at the seed's 2560x1440; the rate only with VRCS.
  const SeedTable& doom = seeds[1];
  EXPECT_EQ(doom.column_option, "vrcs");
  const SeedPlatform* off = doom.find("xbox-series-x", "no_vrcs");
  const SeedPlatform* on = doom.find("xbox-series-x", "vrcs");
  ASSERT_TRUE(off && on);
  EXPECT_EQ(on->width, 2560u);
  EXPECT_DOUBLE_EQ(off->ms.at("deferred_texturing"), 4.20);
  EXPECT_DOUBLE_EQ(on->ms.at("deferred_lighting"), 1.32);
  EXPECT_EQ(off->ms.count("vrcs_shading_rate"), 0u);
  EXPECT_DOUBLE_EQ(on->ms.at("vrcs_shading_rate"), 0.41);
  // The column option is one the technique has and can read back.
  const auto& opts = technique_options(find_technique("deferred"));
  auto it = std::find_if(opts.begin(), opts.end(), [](auto& o) { return o.name == "vrcs"; });
  ASSERT_NE(it, opts.end());
  ASSERT_TRUE(it->read);
  Settings s = apply_preset(find_technique("deferred"), "high", Settings{});
  EXPECT_EQ(it->read(apply_options(find_technique("deferred"), s, {{"vrcs", 0}})), 0.0);
  EXPECT_EQ(it->read(apply_options(find_technique("deferred"), s, {{"vrcs", 1}})), 1.0);
  // God of War Ragnarok: PS5 at 4K, its own workload (not the ps5 profile's 2560x1440); the
  // shadow captions' two views and the reflections' capture as columns, every one compared.
  const SeedTable& gow = seeds[4];
  EXPECT_EQ(gow.name, "god_of_war_ragnarok");
  EXPECT_EQ(gow.technique, "gow-ragnarok");
  EXPECT_TRUE(gow.own_workload);
  EXPECT_TRUE(gow.column_option.empty());
  const SeedPlatform* shot1 = gow.find("ps5", "shot_1");
  const SeedPlatform* shot2 = gow.find("ps5", "shot_2");
  const SeedPlatform* refl = gow.find("ps5", "rt_cubemaps");
  ASSERT_TRUE(shot1 && shot2 && refl);
  EXPECT_EQ(shot1->width, 3840u);
  EXPECT_EQ(refl->height, 2160u);
  EXPECT_DOUBLE_EQ(shot1->ms.at("pcf"), 1.30);
  EXPECT_DOUBLE_EQ(shot1->ms.at("contact_hardening"), 3.22);
  EXPECT_DOUBLE_EQ(shot2->ms.at("pcf"), 0.89);
  EXPECT_DOUBLE_EQ(shot2->ms.at("contact_hardening"), 3.15);
  EXPECT_NEAR(refl->ms.at("bvh_trace_plus_combine_half_res"), 1.33 + 0.68, 1e-12);  // one pass of ours does both
  EXPECT_DOUBLE_EQ(refl->ms.at("resolve_full_res"), 1.36);
  EXPECT_DOUBLE_EQ(refl->ms.at("ssr_ssdo_ssgi"), 4.23);
  EXPECT_EQ(gow.pass_row.at("ssdo_ssgi"), "ssr_ssdo_ssgi");
  EXPECT_EQ(gow.pass_row.at("ssdo"), "ssr_ssdo_ssgi");
  EXPECT_EQ(gow.pass_row.at("ssgi"), "ssr_ssdo_ssgi");
  EXPECT_EQ(gow.pass_row.count("cubemap_capture"), 0u);  // baked offline in the game
  // Its malformed fields are named.
  auto e = [&](const std::string& text) {
    try {
      parse_seed_tables(text, "s.json");
    } catch (const PerfError& err) {
      return std::string(err.what());
    }
    return std::string("no error");
  };
  const std::string all = read_text_file(dir + "/seed-timings.json");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = all;
    const size_t at = text.find(from, text.find("\"god_of_war_ragnarok\""));
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  };
  std::string broken = with("\"pcf\": [1.30, 0.89]", "\"pcf\": [1.30]");
  EXPECT_NE(e(broken).find("/god_of_war_ragnarok/shadows_ps5_4k_ms/pcf: expected [view 1, view 2]"), std::string::npos)
      << e(broken);
  broken = with("\"resolution\": [3840, 2160]", "\"resolution\": [3840]");
  EXPECT_NE(e(broken).find("/god_of_war_ragnarok/workload/resolution"), std::string::npos) << e(broken);
  broken = with("\"resolve_full_res\": 1.36", "\"resolve_full_res\": \"slow\"");
  EXPECT_NE(e(broken).find("/god_of_war_ragnarok/raytraced_cubemaps_ps5_4k_ms/resolve_full_res: expected milliseconds"),
            std::string::npos)
      << e(broken);
}

// ---------------------------------------------------------------- project files (no GPU)

// Runs a test body with `dir` as the working folder and GIB_DATA_DIR unset, restoring both.
class InWorkingFolder {
 public:
  explicit InWorkingFolder(const std::filesystem::path& dir) : was_(std::filesystem::current_path()) {
    if (const char* e = std::getenv("GIB_DATA_DIR")) data_dir_ = e;
    ::unsetenv("GIB_DATA_DIR");
    std::filesystem::current_path(dir);
  }
  ~InWorkingFolder() {
    std::filesystem::current_path(was_);
    if (data_dir_) ::setenv("GIB_DATA_DIR", data_dir_->c_str(), 1);
  }

 private:
  std::filesystem::path was_;
  std::optional<std::string> data_dir_;
};

std::string perf_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const PerfError& e) {
    return e.what();
  }
  return "";
}

// A packed binary runs where its build's source tree does not exist: --case names resolve in
// the working folder first (its cases/ and cases/scenes/, as `gibench run` reads ./cases), and a
// name there hides the source tree's file of that name; the source tree is the fallback.
TEST(PerfProjectFiles, CaseNamesResolveInTheWorkingFolderFirst) {
  namespace fs = std::filesystem;
  test::TempDir dir("gib_perf_cwd_");
  fs::create_directories(dir.path() / "cases" / "scenes");
  dir.write("cases/scenes/room.json", R"({"objects": []})");
  dir.write("cases/lit-room.json", R"({"description": "a case", "scene": "scenes/room.json"})");
  dir.write("cases/scenes/cornell.json", R"({"objects": []})");  // hides the source tree's cornell
  InWorkingFolder here(dir.path());
  const fs::path cwd = fs::current_path();
  EXPECT_EQ(fs::weakly_canonical(resolve_case_scene("lit-room")), cwd / "cases" / "scenes" / "room.json")
      << "a case: its scene, relative to the case file";
  EXPECT_EQ(fs::path(resolve_case_scene("room")), cwd / "cases" / "scenes" / "room.json");
  EXPECT_EQ(fs::weakly_canonical(resolve_case_scene("cases/lit-room.json")), cwd / "cases" / "scenes" / "room.json")
      << "a path relative to the working folder";
  EXPECT_EQ(fs::path(resolve_case_scene("cornell")), cwd / "cases" / "scenes" / "cornell.json");
  // Only in the source tree: found there.
  const fs::path found = resolve_case_scene("glossy_hall");
  EXPECT_EQ(fs::weakly_canonical(found), fs::weakly_canonical(fs::path(GIB_SOURCE_DIR) / "cases/scenes/glossy_hall.json"));
}

TEST(PerfProjectFiles, MissingCaseNameIsOneLineListingEveryPlaceTried) {
  namespace fs = std::filesystem;
  test::TempDir dir("gib_perf_cwd_");
  InWorkingFolder here(dir.path());
  const fs::path cwd = fs::current_path(), src(GIB_SOURCE_DIR);
  const std::string e = perf_error([] { resolve_case_scene("no-such-case"); });
  SCOPED_TRACE(e);
  ASSERT_FALSE(e.empty()) << "a missing name must throw PerfError";
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  EXPECT_EQ(e.rfind("--case: expected a case or scene name", 0), 0u) << "names the flag first";
  EXPECT_NE(e.find("got 'no-such-case'"), std::string::npos);
  for (const fs::path& p : {cwd / "cases/no-such-case.json", cwd / "cases/scenes/no-such-case.json",
                            src / "cases/no-such-case.json", src / "cases/scenes/no-such-case.json"})
    EXPECT_NE(e.find(p.string()), std::string::npos) << "not listed: " << p;
  EXPECT_LT(e.find(cwd.string()), e.find(src.string() + "/cases")) << "the working folder is tried first";
  // The pass benchmarks' scene lookup says the same.
  const std::string s = perf_error([] { find_project_file("cases/scenes/nowhere.json", "GIB_BENCH_CASE 'nowhere'"); });
  EXPECT_EQ(s.rfind("GIB_BENCH_CASE 'nowhere': expected cases/scenes/nowhere.json", 0), 0u) << s;
  EXPECT_NE(s.find((cwd / "cases/scenes/nowhere.json").string()), std::string::npos) << s;
  EXPECT_NE(s.find((src / "cases/scenes/nowhere.json").string()), std::string::npos) << s;
}

// data/ and bench/history.jsonl follow the same order: the working folder's, else the source
// tree's.
TEST(PerfProjectFiles, DataAndHistoryComeFromTheWorkingFolderFirst) {
  namespace fs = std::filesystem;
  test::TempDir dir("gib_perf_cwd_");
  {
    InWorkingFolder here(dir.path());
    EXPECT_EQ(fs::weakly_canonical(default_history_path()), fs::weakly_canonical(fs::path(GIB_SOURCE_DIR) / "bench/history.jsonl"))
        << "no bench/ here: the source tree's";
  }
  fs::create_directories(dir.path() / "data");
  fs::create_directories(dir.path() / "bench");
  fs::copy_file(fs::path(GIB_SOURCE_DIR) / "data/console-profiles.json", dir.path() / "data/console-profiles.json");
  InWorkingFolder here(dir.path());
  const fs::path cwd = fs::current_path();
  EXPECT_EQ(fs::path(find_data_dir("")), fs::weakly_canonical(cwd / "data"));
  EXPECT_EQ(fs::path(default_history_path()), cwd / "bench" / "history.jsonl");
}

// bench plans the contract AOVs the scene supports (not only radiance), so gow-ragnarok's
// reflection passes, which feed only the `reflection` AOV, are planned in a glossy scene and
// culled with a reason in a scene without glossy materials; --aov narrows it.
TEST(PerfPlan, ReflectionPassesArePlannedInAGlossySceneAndCulledWithAReasonElsewhere) {
  const Technique& t = find_technique("gow-ragnarok");
  const char* reflection_passes[] = {"cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"};
  auto plan_of = [&](const Scene& scene, const BenchOutputs& outs) {
    Settings s = apply_preset(t, "medium", Settings{});
    s.width = 64;
    s.height = 36;
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
    return compile(decls, {scene.features(), outs.resources, s.width, s.height});
  };
  Scene glossy = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/glossy_hall.json");
  BenchOutputs outs = bench_outputs(t, glossy.features());
  EXPECT_EQ(outs.aovs, (std::vector<std::string>{"radiance", "direct", "indirect_diffuse", "reflection"}));
  EXPECT_TRUE(outs.left_out.empty());
  Plan plan = plan_of(glossy, outs);
  for (const char* name : reflection_passes) {
    auto it = std::find_if(plan.passes.begin(), plan.passes.end(), [&](auto& pp) { return pp.name == name; });
    ASSERT_NE(it, plan.passes.end()) << name;
    EXPECT_TRUE(it->runs) << name << ": " << it->reason;
  }
  // Radiance alone (what bench planned before): the reflection passes are culled.
  Plan radiance = plan_of(glossy, bench_outputs(t, glossy.features(), {"radiance"}));
  for (auto& pp : radiance.passes)
    if (pp.name.rfind("reflections_", 0) == 0 || pp.name == "cubemap_capture") {
      EXPECT_FALSE(pp.runs) << pp.name;
    }

  Scene matte = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/contact_shadows.json");
  ASSERT_FALSE(matte.features().has(Feature::glossy));
  BenchOutputs mouts = bench_outputs(t, matte.features());
  EXPECT_EQ(mouts.aovs, (std::vector<std::string>{"radiance", "direct", "indirect_diffuse"}));
  ASSERT_EQ(mouts.left_out.size(), 1u);
  EXPECT_EQ(mouts.left_out[0], "reflection (the scene lacks the features it needs)");
  Plan mplan = plan_of(matte, mouts);
  for (const char* name : reflection_passes) {
    auto it = std::find_if(mplan.passes.begin(), mplan.passes.end(), [&](auto& pp) { return pp.name == name; });
    ASSERT_NE(it, mplan.passes.end()) << name;
    EXPECT_FALSE(it->runs) << name;
    EXPECT_FALSE(it->reason.empty()) << name;
  }
  // --aov: narrows; a name outside the contract names the flag.
  EXPECT_EQ(bench_outputs(t, glossy.features(), {"reflection"}).resources, (std::vector<std::string>{"reflection"}));
  EXPECT_THROW(bench_outputs(t, glossy.features(), {"specular"}), PerfError);
  EXPECT_TRUE(bench_outputs(find_technique("direct"), glossy.features(), {"reflection"}).aovs.empty());
}

// What planning every contract AOV changes for bench's frame totals: in every scene of
// cases/scenes, the only running passes that feed no radiance are gow-ragnarok's reflection
// passes in glossy scenes and its direct_aov (the `direct` AOV of the combined screen-space
// pass) in every scene; every other technique plans the same passes as with radiance alone
// (bench/README.md "What is planned"; update it with this list).
TEST(PerfPlan, OnlyGowReflectionAndDirectAovPassesAreAovOnlyInAnyScene) {
  namespace fs = std::filesystem;
  std::set<std::string> aov_only;
  for (auto& e : fs::directory_iterator(std::string(GIB_SOURCE_DIR) + "/cases/scenes")) {
    if (e.path().extension() != ".json") continue;
    Scene scene = load_scene(e.path().string());
    for (const Technique& t : techniques()) {
      Settings s = apply_preset(t, "low", Settings{});
      s.width = 64;
      s.height = 36;
      std::vector<PassDecl> decls;
      for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
      Plan all = compile(decls, {scene.features(), bench_outputs(t, scene.features()).resources, s.width, s.height});
      Plan radiance = compile(decls, {scene.features(), {t.output}, s.width, s.height});
      for (const PlannedPass* pp : all.running())
        if (std::none_of(radiance.passes.begin(), radiance.passes.end(),
                         [&](const PlannedPass& q) { return q.name == pp->name && q.runs; }))
          aov_only.insert(t.name + "/" + pp->name + (scene.features().has(Feature::glossy) ? "" : " (not glossy)"));
    }
  }
  EXPECT_EQ(aov_only, (std::set<std::string>{"gow-ragnarok/cubemap_capture", "gow-ragnarok/reflections_rt_cubemap",
                                             "gow-ragnarok/reflections_resolve", "gow-ragnarok/direct_aov",
                                             "gow-ragnarok/direct_aov (not glossy)"}));
}

// PassDecl::traces_rays is declared by exactly the passes whose own shaders (the pass's folder)
// include the BVH walk, so bench's "software BVH" caveat cannot miss a tracing pass.
// irradiance_volume_update walks it only for a ray whose cache cell was dropped (0 rays at steady
// state on thin-wall-leak-005 at high: no insertion dropped), so it does not declare it.
TEST(PerfPlan, TracingPassesAreThoseWhoseShadersWalkTheBvh) {
  namespace fs = std::filesystem;
  const std::set<std::string> rare_walk = {"irradiance_volume_update"};
  std::map<std::string, bool> walks;  // pass folder -> a shader in it includes bvh.glsl / bvh_alpha.glsl
  for (auto& e : fs::recursive_directory_iterator(std::string(GIB_SOURCE_DIR) + "/renderer")) {
    const std::string ext = e.path().extension().string();
    if (ext != ".comp" && ext != ".glsl" && ext != ".frag" && ext != ".vert") continue;
    std::ifstream in(e.path());
    std::stringstream text;
    text << in.rdbuf();
    const std::string src = text.str();
    const bool includes = src.find("#include \"bvh.glsl\"") != std::string::npos ||
                          src.find("#include \"bvh_alpha.glsl\"") != std::string::npos;
    bool& w = walks[e.path().parent_path().filename().string()];
    w = w || includes;
  }
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/thin_wall_005.json");
  size_t tracing = 0;
  for (const Technique& t : techniques()) {
    Settings s = apply_preset(t, "low", Settings{});
    for (auto& p : make_passes(t)) {
      const PassDecl d = p->declare(scene, s);
      auto it = walks.find(d.name);
      ASSERT_NE(it, walks.end()) << t.name << "/" << d.name << ": no shader folder named after the pass";
      const bool expected = it->second && !rare_walk.count(d.name);
      EXPECT_EQ(d.traces_rays, expected) << t.name << "/" << d.name;
      tracing += d.traces_rays;
    }
  }
  EXPECT_GE(tracing, 12u);  // the walk is found at all (direct_lighting counts once per technique)
}

// ... and timed: one frame through the executor with bench's outputs times every reflection pass.
class PerfPlanGpu : public test::GpuTest {};
TEST_F(PerfPlanGpu, ReflectionPassesAreTimedInAGlossyScene) {
  const Technique& t = find_technique("gow-ragnarok");
  Scene glossy = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/glossy_hall.json");
  Settings s = apply_preset(t, "low", Settings{});
  s.width = 32;
  s.height = 18;
  Executor ex(gpu(), glossy, s, make_passes(t), bench_outputs(t, glossy.features()).resources);
  FrameTiming ft = time_frames(ex, 0, 1);
  std::set<std::string> timed;
  for (auto& [name, summary] : ft.passes()) timed.insert(name);
  for (const char* name : {"cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"})
    EXPECT_TRUE(timed.count(name)) << name;
}

TEST(PerfSamples, ReadsBothFormatsAndNamesBadFields) {
  SampleFile g = parse_sample_file(
      R"({"format": "gibench-perf-1", "device": {"name": "dev"}, "runs": [{"passes": [{"key": "t/p/8x8",
          "samples_ms": [1.0, 2.0]}], "frame": {"key": "t/frame/8x8", "samples_ms": [3.0]}}],
          "noise_floor": {"t/p/8x8": {"detectable_regression": 0.05}}})",
      "a.json");
  EXPECT_EQ(g.device, "dev");
  EXPECT_EQ(g.samples.at("t/p/8x8").size(), 2u);
  EXPECT_EQ(g.samples.at("t/frame/8x8").size(), 1u);
  EXPECT_DOUBLE_EQ(g.detectable.at("t/p/8x8"), 0.05);

  SampleFile b = parse_sample_file(
      R"({"context": {}, "benchmarks": [
          {"name": "x/repeats:2", "run_name": "x", "run_type": "iteration", "real_time": 2000, "time_unit": "us"},
          {"name": "x/repeats:2", "run_name": "x", "run_type": "iteration", "real_time": 3, "time_unit": "ms"},
          {"name": "x_mean", "run_name": "x", "run_type": "aggregate", "real_time": 2.5, "time_unit": "ms"}]})",
      "gb.json");
  ASSERT_EQ(b.samples.at("x").size(), 2u);
  EXPECT_DOUBLE_EQ(b.samples.at("x")[0], 2.0);

  std::string e = error_of([] {
    parse_sample_file(R"({"format": "gibench-perf-1", "runs": [{"passes": [{"key": "k", "samples_ms": [1, -2]}]}]})",
                      "bad.json");
  });
  EXPECT_NE(e.find("bad.json: /runs/0/passes/0/samples_ms"), std::string::npos) << e;
  e = error_of([] { parse_sample_file(R"({"something": 1})", "other.json"); });
  EXPECT_NE(e.find("other.json"), std::string::npos) << e;
}

}  // namespace
}  // namespace gib::perf

namespace gib::perf {
namespace {

TEST(PerfVariants, ParsesLabelAndOptions) {
  BenchVariant v = parse_variant("norays:probe_rays=0,probe_spacing=0.25");
  EXPECT_EQ(v.label, "norays");
  ASSERT_EQ(v.options.size(), 2u);
  EXPECT_EQ(v.options.at("probe_rays"), 0.0);
  EXPECT_EQ(v.options.at("probe_spacing"), 0.25);
  EXPECT_EQ(parse_variant("x:a=1e-3").options.at("a"), 1e-3);
}

TEST(PerfVariants, MalformedVariantsNameTheFlagAndTheExpectedForm) {
  for (const char* bad : {"norays", ":a=1", "l:", "l:a", "l:=1", "l:a=", "l:a=1x", "l:a=1,,b=2"}) {
    try {
      parse_variant(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const PerfError& e) {
      std::string m = e.what();
      EXPECT_NE(m.find("--variant"), std::string::npos) << m;
      EXPECT_NE(m.find("expected"), std::string::npos) << m;
    }
  }
}
}  // namespace
}  // namespace gib::perf

namespace gib::perf {
namespace {
// The calibration measures FP32 with two differently written kernels, interleaved, and keeps
// the faster; both are recorded and survive the JSON round trip. (Whether they agree within a
// few percent is a speed figure: `gibench bench` prints both and their ratio.)
class PerfCalibration : public test::GpuTest {};
TEST_F(PerfCalibration, BothFmaKernelsAreTimedAndTheFasterCounts) {
  Calibration c = calibrate(gpu(), 2);
  ASSERT_EQ(c.fma_ms.size(), 2u);
  ASSERT_EQ(c.fma_scalar_ms.size(), 2u);
  EXPECT_GT(c.fma_gflops, 0.0);
  EXPECT_GT(c.fma_scalar_gflops, 0.0);
  EXPECT_EQ(c.throughput.fp32_gflops, std::max(c.fma_gflops, c.fma_scalar_gflops));
  EXPECT_GT(c.throughput.bandwidth_gbs, 0.0);
  Calibration back = Calibration::from_json(c.to_json());
  EXPECT_EQ(back.fma_gflops, c.fma_gflops);
  EXPECT_EQ(back.fma_scalar_gflops, c.fma_scalar_gflops);
  EXPECT_EQ(back.fma_scalar_ms, c.fma_scalar_ms);
  EXPECT_EQ(back.throughput.fp32_gflops, c.throughput.fp32_gflops);
  EXPECT_GT(c.throughput.fill_gpix, 0.0);
  EXPECT_EQ(c.raster_ms.size(), 2u);
  EXPECT_EQ(back.throughput.fill_gpix, c.throughput.fill_gpix);
  EXPECT_EQ(back.raster_layers, c.raster_layers);
  EXPECT_EQ(back.fill_gpix_of(back.raster_ms), c.throughput.fill_gpix);
  // Dispatch latency: GPUs only (a CPU device's host clock around one submission says nothing
  // about one dispatch); it survives the JSON either way.
  if (gpu().info().is_software()) {
    EXPECT_EQ(c.dispatch_latency_ms, 0.0);
    EXPECT_TRUE(c.dispatch_chain_ms.empty());
  } else {
    EXPECT_EQ(c.dispatch_chain_ms.size(), 2u);
    EXPECT_GT(c.dispatch_latency_ms, 0.0);
  }
  EXPECT_EQ(back.dispatch_latency_ms, c.dispatch_latency_ms);
  EXPECT_EQ(back.dispatch_chain_ms, c.dispatch_chain_ms);
}

// The fill rate counts layers x width x height pixels per draw: true only if every layer's
// every fragment passes the depth test. After a draw the target holds the last layer's id and
// depth everywhere (a layer that failed anywhere would leave an earlier id there).
TEST_F(PerfCalibration, RasterDrawWritesEveryLayerEverywhere) {
  auto pipe = raster_calibration_pipeline(gpu());
  auto color = gpu().create_image(Format::rg32_uint, 37, 21, "raster_test_color");
  auto depth = gpu().create_image(Format::d32_float, 37, 21, "raster_test_depth");
  for (uint32_t layers : {1u, 7u, 64u}) {
    EXPECT_GT(time_raster(gpu(), *pipe, *color, *depth, layers), 0.0);
    const std::vector<uint8_t> c = gpu().download(*color);
    const std::vector<uint8_t> d = gpu().download(*depth);
    ASSERT_EQ(c.size(), 37u * 21u * 8u);
    ASSERT_EQ(d.size(), 37u * 21u * 4u);
    const float z = 1.0f - float(layers) / float(layers + 1);
    size_t wrong = 0;
    for (size_t i = 0; i < 37u * 21u; ++i) {
      uint32_t id, zbits;
      float dz;
      std::memcpy(&id, &c[i * 8], 4);
      std::memcpy(&zbits, &c[i * 8 + 4], 4);
      std::memcpy(&dz, &d[i * 4], 4);
      float fz;
      std::memcpy(&fz, &zbits, 4);
      wrong += id != layers - 1 || std::fabs(fz - z) > 1e-6f || std::fabs(dz - z) > 1e-6f;
    }
    EXPECT_EQ(wrong, 0u) << layers << " layers";
  }
}
}  // namespace
}  // namespace gib::perf

namespace gib::perf {
namespace {
// The clock probe (perf/clock_probe.h): a fixed dispatch, timed, against the fastest the same
// dispatch ran on this device in this process. Whether a GPU's clock holds is a figure (`gibench
// timing` prints the ratio per repeat, rows carry it), not an assertion; time_frames probes only
// on a GPU, so on lavapipe its FrameTiming has no clock record.
class ClockProbeTest : public test::GpuTest {};
TEST_F(ClockProbeTest, ProbeTracksTheFastestAndTheRatioIsTheWorseSide) {
  ClockProbe p(gpu());
  double a = p.probe(), b = p.probe();
  EXPECT_GT(a, 0.0);
  EXPECT_GT(b, 0.0);
  EXPECT_LE(p.fastest(), std::min(a, b) * (1 + 1e-12));
  EXPECT_GT(p.fastest(), 0.0);
  ClockCheck c;
  EXPECT_FALSE(c.measured());
  EXPECT_EQ(c.ratio(), 0.0);
  c.fastest_probe_ms = 0.25;
  c.before_probe_ms = 0.30;
  c.after_probe_ms = 0.75;
  EXPECT_TRUE(c.measured());
  EXPECT_DOUBLE_EQ(c.ratio(), 3.0);
  c.before_probe_ms = 1.0;
  EXPECT_DOUBLE_EQ(c.ratio(), 4.0);
}
}  // namespace
}  // namespace gib::perf
