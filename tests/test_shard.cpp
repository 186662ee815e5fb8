// Sharding the suite: --shard K/N and the GTEST sharding variables pick a
// deterministic 1/N of the rows; `merge` joins the shards into the verdicts of one whole run and
// refuses a missing, duplicated or foreign shard.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/case.h"
#include "harness/suite.h"
#include "harness/shard.h"
#include "tests/suite_fixture.h"
#include "tests/temp_dir.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

TEST(Shard, ParsesKOverNAndRejectsEverythingElseNamingTheFlag) {
  Shard s = parse_shard("1/3");
  EXPECT_EQ(s.index, 1u);
  EXPECT_EQ(s.count, 3u);
  EXPECT_TRUE(s.active());
  EXPECT_FALSE(parse_shard("0/1").active());
  for (const char* bad : {"3/3", "1/0", "1", "a/2", "-1/2", "1/2/3", "1/2x", " 1/2", ""}) {
    SCOPED_TRACE(bad);
    try {
      parse_shard(bad);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--shard: expected K/N"), std::string::npos) << e.what();
    }
  }
}

TEST(Shard, GtestShardingVariablesAreHonouredAndTheStatusFileTouched) {
  test::TempDir dir("gib_shard_env_");
  fs::path status = dir.path() / "status";
  ::setenv("GTEST_SHARD_INDEX", "2", 1);
  ::setenv("GTEST_TOTAL_SHARDS", "4", 1);
  ::setenv("GTEST_SHARD_STATUS_FILE", status.c_str(), 1);
  Shard s = shard_from("");
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 4u);
  EXPECT_TRUE(fs::exists(status));
  Shard flag = shard_from("0/2");  // the flag wins
  EXPECT_EQ(flag.count, 2u);
  ::setenv("GTEST_SHARD_INDEX", "4", 1);
  EXPECT_THROW(shard_from(""), std::invalid_argument);
  ::unsetenv("GTEST_SHARD_INDEX");
  ::unsetenv("GTEST_TOTAL_SHARDS");
  ::unsetenv("GTEST_SHARD_STATUS_FILE");
  EXPECT_FALSE(shard_from("").active());
}

// Every row of the committed suite falls in exactly one shard, for every N, and the shards'
// sizes differ by at most one.
TEST(Shard, EveryCommittedRowIsInExactlyOneShard) {
  std::vector<std::string> plan = plan_rows(load_cases(std::string(GIB_SOURCE_DIR) + "/cases"));
  ASSERT_GE(plan.size(), 40u);
  EXPECT_EQ(std::set<std::string>(plan.begin(), plan.end()).size(), plan.size()) << "row keys are unique";
  for (uint32_t n = 1; n <= 5; ++n) {
    std::vector<size_t> sizes(n, 0);
    for (size_t i = 0; i < plan.size(); ++i) ++sizes[i % n];
    size_t total = 0;
    for (size_t s : sizes) total += s;
    EXPECT_EQ(total, plan.size());
    EXPECT_LE(*std::max_element(sizes.begin(), sizes.end()) - *std::min_element(sizes.begin(), sizes.end()), 1u);
  }
}

// Two 16x8 Cornell cases: direct (with a flip bound it meets), the reference row, and a negative
// control that must be caught: five rows.
void write_cases(const fs::path& cases) {
  fs::create_directories(cases);
  for (const char* name : {"alpha", "beta"}) {
    json c = {{"description", "tiny case for the shard tests"},
              {"scene", std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"},
              {"width", 16},
              {"height", 8},
              {"reference_spp", 4},
              {"techniques",
               {{{"technique", "direct"}, {"presets", {"medium"}}, {"thresholds", {{{"metric", "flip"}, {"max", 0.99}}}}},
                {{"technique", "reference"},
                 {"presets", {"low"}},
                 {"spp", 4},
                 {"thresholds", {{{"metric", "flip"}, {"max", 0.99}}}}}}}};
    if (std::string(name) == "beta")
      c["negative_controls"] = {{{"name", "identical"},
                                 {"why", "direct light alone is not the full radiance"},
                                 {"technique", "direct"},
                                 {"presets", {"medium"}},
                                 {"thresholds", {{{"metric", "flip"}, {"max", 0.0}}}}}};
    std::ofstream(cases / (std::string(name) + ".json")) << c.dump(2);
  }
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

std::map<std::string, std::string> verdicts(const json& results) {
  std::map<std::string, std::string> v;
  for (auto& r : results["results"])
    v[r["case"].get<std::string>() + "/" + r["technique"].get<std::string>() + "." + r["preset"].get<std::string>() +
      "/" + r["kind"].get<std::string>()] = r["status"];
  return v;
}

std::string merge_error(const MergeOptions& o) {
  try {
    cmd_merge(o);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Shard, MergedShardsGiveTheVerdictsOfOneRunAndBadShardSetsAreRefused) {
  test::TempDir dir("gib_shard_");
  fs::path cases = dir.path() / "cases";
  write_cases(cases);
  UpdateOptions up = test::approve_goldens(cases, dir.path() / "goldens");

  SuiteOptions run = up.suite;
  run.stability_scan = false;
  run.out = (dir.path() / "whole").string();
  ASSERT_EQ(cmd_run(run), 0);
  json whole = read_json(dir.path() / "whole" / "results.json");
  EXPECT_FALSE(whole.contains("shard"));
  ASSERT_EQ(whole["results"].size(), 5u);

  std::vector<std::string> shard_dirs;
  for (int k = 0; k < 2; ++k) {
    run.shard = std::to_string(k) + "/2";
    run.out = (dir.path() / ("s" + std::to_string(k))).string();
    ASSERT_EQ(cmd_run(run), 0);
    shard_dirs.push_back(run.out);
    json s = read_json(fs::path(run.out) / "results.json");
    EXPECT_EQ(s["shard"]["count"], 2);
    EXPECT_EQ(s["shard"]["plan"].size(), 5u);
    EXPECT_EQ(s["results"].size(), k == 0 ? 3u : 2u);
  }
  MergeOptions mo;
  mo.out = (dir.path() / "merged").string();
  mo.shard_dirs = {shard_dirs[1], shard_dirs[0]};  // any order
  ASSERT_EQ(cmd_merge(mo), 0);
  json merged = read_json(dir.path() / "merged" / "results.json");
  EXPECT_EQ(verdicts(merged), verdicts(whole));
  EXPECT_EQ(merged["merged"]["shards"], 2);
  EXPECT_FALSE(merged.contains("shard"));
  // Rows come back in the plan's order, so the merged report reads like a whole run's.
  for (size_t i = 0; i < whole["results"].size(); ++i)
    EXPECT_EQ(merged["results"][i]["technique"], whole["results"][i]["technique"]);
  std::ifstream junit(dir.path() / "merged" / "junit.xml");
  std::string xml((std::istreambuf_iterator<char>(junit)), {});
  size_t testcases = 0;
  for (size_t p = xml.find("<testcase"); p != std::string::npos; p = xml.find("<testcase", p + 1)) ++testcases;
  EXPECT_EQ(testcases, 5u);
  EXPECT_TRUE(fs::exists(dir.path() / "merged" / "index.html"));
  for (auto& r : merged["results"])
    EXPECT_TRUE(fs::exists(dir.path() / "merged" / "img" / (r["image"].get<std::string>() + ".png"))) << r["image"];

  mo.shard_dirs = {shard_dirs[0]};
  EXPECT_NE(merge_error(mo).find("shard 1/2 missing"), std::string::npos) << merge_error(mo);
  mo.shard_dirs = {shard_dirs[0], shard_dirs[0], shard_dirs[1]};
  EXPECT_NE(merge_error(mo).find("given twice"), std::string::npos) << merge_error(mo);
  mo.shard_dirs = {shard_dirs[0], (dir.path() / "whole").string()};
  EXPECT_NE(merge_error(mo).find("shard: expected the record of a `gibench run --shard K/N`"), std::string::npos)
      << merge_error(mo);
  mo.shard_dirs = {shard_dirs[0], (dir.path() / "nowhere").string()};
  EXPECT_NE(merge_error(mo).find("results.json: expected a shard's results.json"), std::string::npos) << merge_error(mo);

  // A shard that lost a row (a crash mid-run) is caught by name.
  json broken = read_json(fs::path(shard_dirs[1]) / "results.json");
  std::string lost = broken["results"][0]["case"].get<std::string>() + "/" + broken["results"][0]["technique"].get<std::string>();
  broken["results"].erase(broken["results"].begin());
  fs::create_directories(dir.path() / "broken");
  std::ofstream(dir.path() / "broken" / "results.json") << broken.dump();
  mo.shard_dirs = {shard_dirs[0], (dir.path() / "broken").string()};
  std::string err = merge_error(mo);
  EXPECT_NE(err.find("row " + lost), std::string::npos) << err;
  EXPECT_NE(err.find("missing: planned in shard 1/2"), std::string::npos) << err;
}

}  // namespace
}  // namespace gib
