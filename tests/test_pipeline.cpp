// The suite's pipeline stages around the render: the plan and its quick profile, the verdicts,
// progress output, and rows in parallel worker processes (the same rows as a serial run, bit
// for bit).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/jobs.h"
#include "harness/plan.h"
#include "harness/progress.h"
#include "harness/suite.h"
#include "harness/verdict.h"
#include "tests/suite_fixture.h"
#include "tests/temp_dir.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::vector<Case> committed_cases() { return load_cases(std::string(GIB_SOURCE_DIR) + "/cases"); }

TEST(Plan, EveryRowOnceInSuiteOrderWithAPositiveCost) {
  std::vector<Case> cases = committed_cases();
  std::vector<PlannedRow> plan = plan_suite(cases);
  std::set<std::string> keys;
  for (auto& p : plan) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_GT(p.cost, 0) << p.key;
    EXPECT_EQ(p.key.substr(0, p.key.find('/')), cases[p.case_index].name);
    EXPECT_EQ(planned_run(cases, p).technique, p.technique);
  }
  EXPECT_EQ(plan_rows(cases).size(), plan.size());
}

TEST(Plan, TheQuickProfileTouchesEveryCaseAndTechniqueAndKeepsEachCasesCheapControl) {
  std::vector<Case> cases = committed_cases();
  std::vector<PlannedRow> plan = plan_suite(cases);
  std::map<std::string, std::string> left_out = select_quick(cases, plan);
  EXPECT_EQ(left_out, select_quick(cases, plan)) << "deterministic";
  std::set<std::string> case_touched, control_kept, techniques, techniques_run;
  double cost_run = 0, cost_all = 0;
  for (auto& p : plan) {
    techniques.insert(p.technique);
    cost_all += p.cost;
    auto it = left_out.find(p.key);
    if (it != left_out.end()) {
      EXPECT_NE(it->second.find("--profile full"), std::string::npos) << "says what runs it: " << it->second;
      continue;
    }
    cost_run += p.cost;
    techniques_run.insert(p.technique);
    if (p.kind == "technique") case_touched.insert(cases[p.case_index].name);
    else control_kept.insert(cases[p.case_index].name);
  }
  for (auto& c : cases) {
    EXPECT_TRUE(case_touched.count(c.name)) << c.name;
    double cheapest_control = std::numeric_limits<double>::infinity();
    for (auto& p : plan)
      if (p.kind == "negative_control" && cases[p.case_index].name == c.name)
        cheapest_control = std::min(cheapest_control, p.cost);
    if (cheapest_control <= kQuickSlowRowSeconds) {
      EXPECT_TRUE(control_kept.count(c.name)) << c.name;
    }
  }
  EXPECT_EQ(techniques_run, techniques);
  EXPECT_LT(cost_run, 0.5 * cost_all) << "the quick profile is a fraction of the suite";
  EXPECT_FALSE(left_out.empty());
}

TEST(Plan, RecordedRowSecondsReplaceTheModelAndABadFileIsNamed) {
  test::TempDir dir("gib_row_seconds_");
  EXPECT_TRUE(load_row_seconds(dir.str()).empty()) << "no file: the model's costs";
  record_row_seconds(dir.str(), {{"a/direct.medium", 12.34}}, "test");
  record_row_seconds(dir.str(), {{"a/negative:off", 3.0}}, "test");  // merged with what is there
  RowSeconds rec = load_row_seconds(dir.str());
  EXPECT_EQ(rec.size(), 2u);
  EXPECT_DOUBLE_EQ(rec["a/direct.medium"], 12.3);
  std::vector<Case> cases = committed_cases();
  std::vector<PlannedRow> plan = plan_suite(cases, {{plan_suite(cases).front().key, 777.0}});
  EXPECT_DOUBLE_EQ(plan.front().cost, 777.0);
  EXPECT_NE(plan[1].cost, 777.0);
  std::ofstream(row_seconds_path(dir.str())) << R"({"rows": {"a/direct.medium": "slow"}})";
  try {
    load_row_seconds(dir.str());
    ADD_FAILURE() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find(row_seconds_path(dir.str()) + ": expected"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/rows/a/direct.medium"), std::string::npos) << e.what();
  }
}

TEST(Plan, ProfileByDeviceAndFlag) {
  EXPECT_EQ(resolve_profile("", true), Profile::quick);
  EXPECT_EQ(resolve_profile("", false), Profile::full);
  EXPECT_EQ(resolve_profile("full", true), Profile::full);
  EXPECT_EQ(resolve_profile("quick", false), Profile::quick);
  try {
    resolve_profile("fast", true);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--profile: expected quick or full, got 'fast'");
  }
}

TEST(Verdict, KnownFailuresAndControlsAreDecidedFromTheChecks) {
  TechniqueRun run;
  run.known_failure = {{"lavapipe", "the leak, 0.6 of the reference"}};
  ResultRow row;
  technique_verdict(row, true, run, "lavapipe", "ci");
  EXPECT_EQ(row.status, "known_failure");
  EXPECT_EQ(row.messages.front(), "known failure: the leak, 0.6 of the reference");
  ResultRow fixed;
  technique_verdict(fixed, false, run, "lavapipe", "ci");
  EXPECT_EQ(fixed.status, "fail") << "a known failure that passes fails, so the mark cannot go stale";
  ResultRow other;
  technique_verdict(other, true, run, "nvidia", "gpu");
  EXPECT_EQ(other.status, "fail");

  NegativeControl nc;
  nc.name = "off";
  nc.why = "mitigations off";
  ResultRow caught;
  caught.checks.push_back({"flip", "reference", "", 0.4, 0.1, std::nullopt, false, false, "flip 0.4 > max 0.1"});
  control_verdict(caught, nc, "lavapipe", "ci");
  EXPECT_EQ(caught.status, "pass");
  ResultRow missed;
  missed.checks.push_back({"flip", "reference", "", 0.01, 0.1, std::nullopt, true, false, "flip ok"});
  control_verdict(missed, nc, "lavapipe", "ci");
  EXPECT_EQ(missed.status, "fail");
  ResultRow unscanned;
  unscanned.checks.push_back({"scan_nan", "", "", 0, 0.0, std::nullopt, true, true, "scan_nan skipped"});
  control_verdict(unscanned, nc, "lavapipe", "ci");
  EXPECT_EQ(unscanned.status, "skipped");
}

TEST(Progress, DurationsAndRecordedRowTimes) {
  EXPECT_EQ(format_duration(0), "0:00");
  EXPECT_EQ(format_duration(65.4), "1:05");
  EXPECT_EQ(format_duration(3723), "1:02:03");
  test::TempDir dir("gib_progress_");
  EXPECT_TRUE(recorded_row_seconds(dir.str()).empty()) << "no results.json: no record";
  std::ofstream(dir.path() / "results.json") << json{
      {"results",
       {{{"case", "a"}, {"kind", "technique"}, {"technique", "direct"}, {"preset", "medium"}, {"wall_s", 2.5}},
        {{"case", "a"}, {"kind", "negative_control"}, {"technique", "direct"}, {"preset", "medium"},
         {"negative_control", "off"}, {"wall_s", 1.0}},
        {{"case", "b"}, {"kind", "technique"}, {"technique", "direct"}, {"preset", "low"}}}}}.dump();
  std::map<std::string, double> rec = recorded_row_seconds(dir.str());
  EXPECT_EQ(rec.size(), 2u);
  EXPECT_DOUBLE_EQ(rec["a/direct.medium"], 2.5);
  EXPECT_DOUBLE_EQ(rec["a/negative:off"], 1.0);
  std::ofstream(dir.path() / "results.json") << "{not json";
  EXPECT_TRUE(recorded_row_seconds(dir.str()).empty());
}

TEST(Jobs, DevicesAndWorkerCounts) {
  EXPECT_TRUE(split_devices("").empty());
  EXPECT_EQ(split_devices("NVIDIA"), std::vector<std::string>{"NVIDIA"});
  EXPECT_EQ(split_devices("0,1"), (std::vector<std::string>{"0", "1"}));
  EXPECT_THROW(split_devices("0,,1"), std::invalid_argument);
  EXPECT_THROW(split_devices("0,"), std::invalid_argument);
  EXPECT_EQ(resolve_jobs(3, true), 3u);
  EXPECT_EQ(resolve_jobs(0, false), kGpuJobs);
  EXPECT_GE(resolve_jobs(0, true), 1u);
}

// A 16x8 Cornell case with these technique runs, rendered in a second.
json tiny_case(const json& techniques) {
  return {{"description", "tiny case for the pipeline tests"},
          {"scene", std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"},
          {"width", 16},
          {"height", 8},
          {"reference_spp", 4},
          {"timing_frames", 1},
          {"techniques", techniques}};
}

// Three 16x8 Cornell cases (direct, the reference row, a negative control): the rows of a run
// in 3 worker processes are the rows of a serial run, with the same verdicts, metrics and
// images (0 differing golden values), in the same order.
TEST(Jobs, ParallelRowsAreTheSerialRowsBitForBit) {
  test::TempDir dir("gib_jobs_");
  fs::path cases = dir.path() / "cases";
  fs::create_directories(cases);
  for (const char* name : {"alpha", "beta", "gamma"}) {
    json c = tiny_case({{{"technique", "direct"},
                         {"presets", {"low", "medium"}},
                         {"thresholds", {{{"metric", "flip"}, {"max", 0.99}}}}},
                        {{"technique", "reference"}, {"presets", {"low"}}, {"spp", 4}}});
    c.update({{"negative_controls",
               {{{"name", "identical"},
                 {"why", "direct light alone is not the full radiance"},
                 {"technique", "direct"},
                 {"thresholds", {{{"metric", "flip"}, {"max", 0.0}}}}}}}});
    std::ofstream(cases / (std::string(name) + ".json")) << c.dump(2);
  }
  UpdateOptions up = test::approve_goldens(cases, dir.path() / "goldens");
  SuiteOptions o = up.suite;
  o.stability_scan = false;
  o.out = (dir.path() / "serial").string();
  ASSERT_EQ(cmd_run(o), 0);
  o.out = (dir.path() / "parallel").string();
  o.jobs = 3;
  o.worker_exe = GIBENCH_EXE;
  ASSERT_EQ(cmd_run(o), 0);
  auto read = [](const fs::path& p) { return json::parse(std::ifstream(p / "results.json")); };
  json serial = read(dir.path() / "serial"), parallel = read(dir.path() / "parallel");
  ASSERT_EQ(serial["results"].size(), 12u);
  ASSERT_EQ(parallel["results"].size(), serial["results"].size());
  EXPECT_EQ(parallel["run"]["jobs"], 3);
  for (size_t i = 0; i < serial["results"].size(); ++i) {
    const json &s = serial["results"][i], &p = parallel["results"][i];
    SCOPED_TRACE(s["case"].get<std::string>() + "/" + s["technique"].get<std::string>());
    EXPECT_EQ(p["case"], s["case"]);
    EXPECT_EQ(p["technique"], s["technique"]);
    EXPECT_EQ(p["kind"], s["kind"]);
    EXPECT_EQ(p["status"], s["status"]);
    EXPECT_EQ(p["metrics"]["flip_vs_reference"], s["metrics"]["flip_vs_reference"]);
    if (s["kind"] == "technique") {
      EXPECT_EQ(p["metrics"]["golden_differing_values"], 0);
    }
    EXPECT_GT(p["wall_s"].get<double>(), 0);
    const std::string image = s["image"];
    EXPECT_TRUE(fs::exists(dir.path() / "parallel" / "img" / (image + ".exr"))) << image;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "parallel" / ".jobs")) << "the workers' folders are removed";
}

// The quick profile lists what it left out as not_run rows (junit: skipped), never as passed.
TEST(Jobs, QuickProfileRowsLeftOutAreListedAsNotRun) {
  test::TempDir dir("gib_quick_");
  fs::path cases = dir.path() / "cases";
  fs::create_directories(cases);
  json c = tiny_case({{{"technique", "direct"}, {"presets", {"low", "medium", "high", "ultra"}}}});
  std::ofstream(cases / "solo.json") << c.dump(2);
  UpdateOptions up = test::approve_goldens(cases, dir.path() / "goldens");
  SuiteOptions o = up.suite;
  o.stability_scan = false;
  o.profile = "quick";
  o.out = (dir.path() / "out").string();
  ASSERT_EQ(cmd_run(o), 0);
  json r = json::parse(std::ifstream(dir.path() / "out" / "results.json"));
  ASSERT_EQ(r["results"].size(), 4u);
  size_t not_run = 0;
  for (auto& row : r["results"]) {
    if (row["status"] != "not_run") continue;
    ++not_run;
    EXPECT_NE(row["messages"][0].get<std::string>().find("quick profile"), std::string::npos);
  }
  EXPECT_EQ(not_run, 3u) << "the cheapest row (low) is also the one of every 4th that runs";
  EXPECT_EQ(r["run"]["profile"], "quick");
  std::ifstream junit(dir.path() / "out" / "junit.xml");
  std::string xml((std::istreambuf_iterator<char>(junit)), {});
  EXPECT_NE(xml.find("<skipped message=\"not run by the quick profile"), std::string::npos);
}

}  // namespace
}  // namespace gib
