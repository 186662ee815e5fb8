// Goldens and references: the 3x noise-floor rule on flip bounds against the
// reference, what update-goldens --reference records in golden.json (spp, seed, device, driver,
// noise floor per file), that a file is read only with its record, the --spp override and the
// spp split, atomic golden writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "harness/case.h"
#include "tests/temp_dir.h"
#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/suite.h"
#include "tests/gpu_fixture.h"
#include "tests/suite_fixture.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A fresh directory per test, removed afterwards.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("gib_goldens_") {}
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// ---------------------------------------------------------------- the 3x rule (no GPU)

Case rule_case(double flip_max, const std::string& compare_aov = "", const std::string& roi = "") {
  Case c;
  c.name = "rule";
  c.file = "cases/rule.json";
  c.output = "radiance";
  TechniqueRun run;
  run.technique = "radiance-cache";
  run.presets = {"medium"};
  run.compare_aov = compare_aov;
  Threshold t;
  t.metric = "flip";
  t.against = "reference";
  t.roi = roi;
  t.max = flip_max;
  run.thresholds = {t};
  c.techniques = {run};
  return c;
}

std::string rule_error(const Case& c, const json& meta) {
  try {
    check_noise_floor_bounds(c, meta, "goldens/rule/golden.json");
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(NoiseFloorRule, ExactlyThreeTimesPassesBelowFailsNamingBothNumbers) {
  json meta = {{"noise_floor", {{"flip", 0.01}, {"aov", "radiance"}, {"spp", 65536}}}};
  EXPECT_EQ(rule_error(rule_case(0.03), meta), "") << "a bound at exactly 3x the floor is allowed";
  EXPECT_EQ(rule_error(rule_case(0.2), meta), "");
  std::string msg = rule_error(rule_case(0.0299), meta);
  SCOPED_TRACE(msg);
  ASSERT_FALSE(msg.empty()) << "a bound below 3x the floor must be rejected";
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line";
  EXPECT_EQ(msg.rfind("cases/rule.json: ", 0), 0u) << "names the case file first";
  for (const char* part : {"radiance-cache (medium)", "max 0.0299", "3 x 0.01 = 0.03", "65536 spp",
                           "goldens/rule/golden.json", "measures the reference, not the technique"})
    EXPECT_NE(msg.find(part), std::string::npos) << "missing: " << part;
}

TEST(NoiseFloorRule, NoFloorOrOtherAovOrRoiIsNotChecked) {
  EXPECT_EQ(rule_error(rule_case(0.0001), json::object()), "") << "golden.json without a noise floor: no check";
  // A floor written before floors named their AOV was measured on the case's output.
  json legacy = {{"noise_floor", {{"flip", 0.088}, {"spp", 256}}}};
  EXPECT_NE(rule_error(rule_case(0.25), legacy), "") << "0.25 < 3 x 0.088 on the output AOV";
  EXPECT_EQ(rule_error(rule_case(0.25, "direct"), legacy), "") << "no floor measured on the direct AOV";
  json per_aov = {{"noise_floor", {{"flip", 0.088}, {"aov", "radiance"}, {"aovs", {{"direct", 0.05}}}, {"spp", 256}}}};
  EXPECT_EQ(rule_error(rule_case(0.15, "direct"), per_aov), "");
  std::string msg = rule_error(rule_case(0.14, "direct"), per_aov);
  EXPECT_NE(msg.find("3 x 0.05 = 0.15"), std::string::npos) << msg;
  EXPECT_NE(msg.find("direct AOV"), std::string::npos) << msg;
  EXPECT_EQ(rule_error(rule_case(0.001, "", "room"), per_aov), "") << "the floor is a whole-image mean";
}

// ---------------------------------------------------------------- atomic writes (no GPU)

// Every committed path-traced reference (a golden.json entry with an "aov") is converged: it
// records spp, seed, device and driver, and a noise floor (FLIP between two seeds, its own AOV)
// of at most kReferenceNoiseFloorMax, so no reference's own noise passes for technique error.
TEST(CommittedReferences, EveryReferenceRecordsItsRenderAndANoiseFloorAtMostOnePercent) {
  int checked = 0;
  for (const auto& dir : fs::directory_iterator(fs::path(GIB_SOURCE_DIR) / "goldens")) {
    fs::path meta_path = dir.path() / "golden.json";
    if (!fs::exists(meta_path)) continue;
    json meta = json::parse(read_text(meta_path));
    for (auto& [name, rec] : meta["files"].items()) {
      if (!rec.contains("aov")) continue;  // an approved technique output
      SCOPED_TRACE(meta_path.string() + ": " + name);
      ++checked;
      EXPECT_GT(rec.value("spp", 0u), 0u);
      EXPECT_TRUE(rec.contains("seed"));
      EXPECT_FALSE(rec.value("device", std::string()).empty());
      EXPECT_FALSE(rec.value("driver", std::string()).empty());
      ASSERT_TRUE(rec.contains("noise_floor")) << "no noise floor recorded";
      EXPECT_EQ(rec["noise_floor"].value("aov", std::string()), rec["aov"].get<std::string>());
      EXPECT_LE(rec["noise_floor"].value("flip", 1.0), kReferenceNoiseFloorMax)
          << "at " << rec["noise_floor"].value("spp", 0u) << " spp: re-render it with ci/gpu_references.sh";
    }
  }
  EXPECT_GE(checked, 30);  // every case's references, not an empty folder
}

TEST(GoldenWrites, FailedMetadataWriteKeepsTheOldFile) {
  TempDir dir;
  GoldenStore store(dir.path().string(), "c");
  store.write_metadata({{"files", {{"reference.exr", {{"spp", 256}}}}}});
  fs::path p = dir.path() / "c" / "golden.json";
  std::string before = read_text(p);
  // Invalid UTF-8 cannot be serialised: the write fails before anything replaces golden.json.
  EXPECT_ANY_THROW(store.write_metadata({{"reason", std::string("bad \xff byte")}}));
  EXPECT_EQ(read_text(p), before);
  for (auto& e : fs::directory_iterator(dir.path() / "c"))
    EXPECT_EQ(e.path().filename(), "golden.json") << "left behind: " << e.path();
}

TEST(GoldenWrites, FailedImageWriteKeepsTheOldFileAndNoStagedFile) {
  TempDir dir;
  GoldenStore store(dir.path().string(), "c");
  store.write("reference", "", FloatImage(4, 2, 4, 0.5f));
  fs::path target = dir.path() / "c" / "reference.exr";
  ASSERT_TRUE(fs::exists(target));
  std::string before = read_text(target);
  // history/ cannot be made (a file is in the way): the replacement fails after staging.
  std::ofstream(dir.path() / "c" / "history") << "in the way";
  EXPECT_ANY_THROW(store.write("reference", "", FloatImage(4, 2, 4, 2.0f)));
  EXPECT_EQ(read_text(target), before);
  for (auto& e : fs::directory_iterator(dir.path() / "c"))
    EXPECT_TRUE(e.path().filename() == "reference.exr" || e.path().filename() == "history") << "left behind: " << e.path();
}

// ---------------------------------------------------------------- records (no GPU)

std::string golden_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const GoldenError& e) {
    return e.what();
  }
  return "";
}

json reference_record() { return {{"aov", "radiance"}, {"spp", 256}, {"seed", 1}, {"device", "a device"}}; }
json technique_record() { return {{"technique", "direct"}, {"preset", "medium"}, {"device", "a device"}}; }

// A golden folder whose golden.json is gone: reading a file from it is one line naming
// golden.json, the file and what its record holds, with how to get it back; the image alone
// (what update-goldens compares with before replacing it) still reads.
TEST(GoldenRecords, FileWithoutGoldenJsonIsOneLineNamingGoldenJsonAndTheFile) {
  TempDir dir;
  GoldenStore store(dir.str(), "c");
  store.write("reference", "", FloatImage(4, 2, 4, 0.5f));
  const std::string path = store.find("reference", "");
  ASSERT_FALSE(path.empty());
  const std::string where = (dir.path() / "c" / "golden.json").string();
  const std::string e = golden_error([&] { store.read(path); });
  SCOPED_TRACE(e);
  ASSERT_FALSE(e.empty()) << "a reference without golden.json must not read silently";
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  EXPECT_EQ(e.rfind(where + ": expected the record of reference.exr (aov, spp, device), got no file; ", 0), 0u);
  EXPECT_NE(e.find("gibench update-goldens --case c --reference"), std::string::npos);
  EXPECT_EQ(store.read_without_record(path).width, 4u);
}

TEST(GoldenRecords, MissingEntryOrFieldIsNamedByItsPointerAndAWholeRecordReads) {
  TempDir dir;
  GoldenStore store(dir.str(), "c");
  store.write("reference", "", FloatImage(4, 2, 4, 0.5f));
  store.write("direct.medium", "", FloatImage(4, 2, 4, 0.25f));
  const std::string ref = store.find("reference", ""), tech = store.find("direct.medium", "");
  const std::string where = (dir.path() / "c" / "golden.json").string();
  store.write_metadata({{"files", {{"direct.medium.exr", technique_record()}}}});
  EXPECT_EQ(store.read(tech).width, 4u) << "an approved output with its record";
  std::string e = golden_error([&] { store.read(ref); });
  EXPECT_EQ(e.rfind(where + ": /files/reference.exr: expected the record of reference.exr (aov, spp, device), got no entry; ", 0), 0u) << e;

  json rec = reference_record();
  rec.erase("spp");
  store.write_metadata({{"files", {{"reference.exr", rec}, {"direct.medium.exr", technique_record()}}}});
  e = golden_error([&] { store.read(ref); });
  EXPECT_EQ(e.rfind(where + ": /files/reference.exr/spp: expected the record of reference.exr (aov, spp, device), got none; ", 0), 0u) << e;
  rec["spp"] = 0;
  store.write_metadata({{"files", {{"reference.exr", rec}, {"direct.medium.exr", technique_record()}}}});
  e = golden_error([&] { store.read(ref); });
  EXPECT_NE(e.find("/files/reference.exr/spp: expected the record of reference.exr (aov, spp, device), got 0; "), std::string::npos) << e;

  store.write_metadata({{"files", {{"reference.exr", reference_record()}}}});
  EXPECT_EQ(store.read(ref).width, 4u) << "a reference with its record";
  EXPECT_EQ(store.record_of("reference.exr")["spp"], 256);
  e = golden_error([&] { store.read(tech); });
  EXPECT_EQ(e.rfind(where + ": /files/direct.medium.exr: expected the record of direct.medium.exr (technique, preset, device), got no entry; ", 0), 0u) << e;
  EXPECT_NE(e.find("gibench update-goldens --case c --technique direct --reason"), std::string::npos) << e;

  // The GPU tier's goldens say so in the command; a reference cache entry is rendered again.
  GoldenStore gpu(dir.str(), "c", "gpu");
  gpu.write("direct.medium", "", FloatImage(4, 2, 4, 0.25f));
  e = golden_error([&] { gpu.read(gpu.find("direct.medium", "")); });
  EXPECT_NE(e.find("--technique direct --tier gpu --reason"), std::string::npos) << e;
  GoldenStore cache(dir.str(), "c", "0123abcd");
  cache.write("reference", "", FloatImage(4, 2, 4, 0.5f));
  e = golden_error([&] { cache.read(cache.find("reference", "")); });
  EXPECT_NE(e.find("gibench references --case c --refresh"), std::string::npos) << e;
}

TEST(GoldenRecords, ReferenceFileNamesAreToldFromApprovedOutputs) {
  for (const char* f : {"reference.exr", "reference.direct.exr", "reference.indirect_diffuse.f010.exr", "reference.f120.exr"})
    EXPECT_TRUE(GoldenStore::is_reference_file(f)) << f;
  for (const char* f : {"reference.medium.exr", "reference.low.nvidia.exr", "direct.medium.exr", "reference.direct.medium.exr",
                        "reference", "reference.json"})
    EXPECT_FALSE(GoldenStore::is_reference_file(f)) << f;
}

// ---------------------------------------------------------------- update-goldens (lavapipe)

// A 16x8 Cornell box, 4 spp by default; one technique row (the reference at low) with a loose
// flip bound against the reference.
void write_tiny_case(const fs::path& cases) {
  fs::create_directories(cases);
  json c = {{"description", "tiny reference case for the goldens tests"},
            {"scene", std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"},
            {"width", 16},
            {"height", 8},
            {"reference_spp", 4},
            {"techniques", {{{"technique", "reference"},
                             {"presets", {"low"}},
                             {"spp", 4},
                             {"thresholds", {{{"metric", "flip"}, {"max", 0.95}}}}}}}};
  std::ofstream(cases / "tiny.json") << c.dump(2);
}

TEST(UpdateGoldens, ReferenceRecordsSppSeedDeviceDriverAndNoiseFloor) {
  TempDir dir;
  write_tiny_case(dir.path() / "cases");
  UpdateOptions o;
  o.suite.cases_dir = (dir.path() / "cases").string();
  o.suite.goldens_dir = (dir.path() / "goldens").string();
  o.suite.validate = true;
  o.reference = true;
  o.reason = "test";
  o.spp = 1024;  // above 512: 32 spp per frame x 32 frames (the GPU split)
  o.noise_floor = true;
  ASSERT_EQ(cmd_update_goldens(o), 0);
  GoldenStore store(o.suite.goldens_dir, "tiny");
  json meta = store.metadata();
  SCOPED_TRACE(meta.dump(2));
  ASSERT_TRUE(meta.contains("noise_floor"));
  const json& nf = meta["noise_floor"];
  EXPECT_EQ(nf["spp"], 1024);
  EXPECT_EQ(nf["seeds"], json({1, 1001}));
  EXPECT_EQ(nf["aov"], "radiance");
  EXPECT_GT(nf["flip"].get<double>(), 0.0) << "two seeds of a noisy image differ";
  EXPECT_EQ(nf["aovs"]["radiance"], nf["flip"]);
  for (const char* name : {"reference.exr", "reference.direct.exr", "reference.indirect_diffuse.exr"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(meta["files"].contains(name));
    const json& f = meta["files"][name];
    EXPECT_EQ(f["spp"], 1024) << "the --spp override, not the case's 4";
    EXPECT_EQ(f["frames"], 32);
    EXPECT_EQ(f["seed"], 1);
    EXPECT_FALSE(f["device"].get<std::string>().empty());
    EXPECT_FALSE(f["driver"].get<std::string>().empty());
    for (const char* k : {"revision", "settings_hash", "date", "reason", "aov"}) EXPECT_TRUE(f.contains(k)) << k;
    ASSERT_TRUE(f.contains("noise_floor"));
    EXPECT_EQ(f["noise_floor"]["spp"], 1024);
    EXPECT_EQ(f["noise_floor"]["seeds"], json({1, 1001}));
    EXPECT_EQ(f["noise_floor"]["aov"], f["aov"]);
    EXPECT_EQ(f["noise_floor"]["flip"], nf["aovs"][f["aov"].get<std::string>()]);
    EXPECT_TRUE(fs::exists(fs::path(store.dir()) / name)) << "references have one file for every device";
  }
  // The technique golden of the reference row keeps the case's budget.
  ASSERT_TRUE(meta["files"].contains("reference.low.exr"));
  EXPECT_EQ(meta["files"]["reference.low.exr"]["spp"], 4);
  EXPECT_FALSE(meta["files"]["reference.low.exr"].contains("noise_floor"));
  Case c = load_case((dir.path() / "cases" / "tiny.json").string());
  EXPECT_EQ(recorded_reference_spp(c, meta), 1024u);

  // A run uses the committed 1024 spp reference as it is: no re-render, no hash check; the
  // 0.95 bound sits above 3x the floor.
  SuiteOptions run = o.suite;
  run.out = (dir.path() / "out").string();
  run.stability_scan = false;
  EXPECT_EQ(cmd_run(run), 0);

  // Again at the case's spp without --noise-floor: the stale floor goes, the old file is kept.
  std::string hash = meta["files"]["reference.exr"]["settings_hash"];
  o.spp = 0;
  o.noise_floor = false;
  ASSERT_EQ(cmd_update_goldens(o), 0);
  json again = store.metadata();
  EXPECT_FALSE(again.contains("noise_floor"));
  const json& f = again["files"]["reference.exr"];
  EXPECT_EQ(f["spp"], 4);
  EXPECT_EQ(f["frames"], 1);
  EXPECT_FALSE(f.contains("noise_floor"));
  EXPECT_NE(f["settings_hash"], hash);
  EXPECT_TRUE(f.contains("flip_vs_previous"));
  ASSERT_TRUE(f.contains("previous"));
  EXPECT_TRUE(fs::exists(fs::path(store.dir()) / "history" / f["previous"].get<std::string>()));
}

// A known_failure mark: a failing run is reported as known_failure and passes the suite; a
// passing run marked on this device's class fails it; a mark for another class is ignored.
TEST(KnownFailure, FailingRunIsKnownPassingRunGoesStaleOtherClassIgnored) {
  TempDir dir;
  fs::path cases = dir.path() / "cases";
  write_tiny_case(cases);
  UpdateOptions o = test::approve_goldens(cases, dir.path() / "goldens");
  json c = json::parse(read_text(cases / "tiny.json"));
  SuiteOptions run = o.suite;
  run.out = (dir.path() / "out").string();
  run.stability_scan = false;
  auto run_with = [&](const json& known, bool impossible_bound) {
    json d = c;
    d["techniques"][0]["known_failure"] = known;
    if (impossible_bound) {
      d["rois"] = {{{"name", "all"}, {"box", {0, 0, 1, 1}}}};
      d["techniques"][0]["thresholds"].push_back({{"metric", "roi_mean"}, {"roi", "all"}, {"min", 1e9}});
    }
    std::ofstream(cases / "tiny.json") << d.dump(2);
    int rc = cmd_run(run);
    json row = json::parse(read_text(fs::path(run.out) / "results.json"))["results"][0];
    return std::make_pair(rc, row);
  };
  auto [rc, row] = run_with("a defect", true);
  EXPECT_EQ(rc, 0) << row.dump(2);
  EXPECT_EQ(row["status"], "known_failure");
  EXPECT_NE(row.dump().find("known failure: a defect"), std::string::npos) << row.dump(2);

  std::tie(rc, row) = run_with("a defect", false);
  EXPECT_NE(rc, 0) << "a marked run that passes fails the suite";
  EXPECT_EQ(row["status"], "fail");
  EXPECT_NE(row.dump().find("marked known_failure on "), std::string::npos) << row.dump(2);

  std::string cls = json::parse(read_text(fs::path(run.out) / "results.json"))["device"]["class"];
  std::string other = cls == "amd" ? "intel" : "amd";
  std::tie(rc, row) = run_with({{other, "another device's defect"}}, false);
  EXPECT_EQ(rc, 0) << row.dump(2);
  EXPECT_EQ(row["status"], "pass");
  std::tie(rc, row) = run_with({{cls, "this device's defect"}}, true);
  EXPECT_EQ(rc, 0) << row.dump(2);
  EXPECT_EQ(row["status"], "known_failure");
}

// Goldens per device class: a row compares with its golden class's approved file;
// where that class has none, the plain (lavapipe) file stands in and the row says so, by name,
// in results.json ("golden_class") and its messages, never silently.
TEST(GoldenClass, RowNamesTheClassItWasComparedWithAndSaysSoWhenAnotherStoodIn) {
  TempDir dir;
  fs::path cases = dir.path() / "cases";
  write_tiny_case(cases);
  UpdateOptions o = test::approve_goldens(cases, dir.path() / "goldens");  // the reference and this device's golden
  SuiteOptions run = o.suite;
  run.out = (dir.path() / "out").string();
  run.stability_scan = false;
  auto row_with = [&](const std::string& golden_class) {
    run.golden_class = golden_class;
    int rc = cmd_run(run);
    json results = json::parse(read_text(fs::path(run.out) / "results.json"));
    return std::make_tuple(rc, results["device"], results["results"][0]);
  };
  auto [rc, device, row] = row_with("");
  const std::string cls = device["class"];
  EXPECT_EQ(rc, 0) << row.dump(2);
  EXPECT_EQ(device["golden_class"], cls);
  EXPECT_EQ(row["golden_class"], cls);
  EXPECT_EQ(row.dump().find("no " + cls + " golden"), std::string::npos) << row.dump(2);

  // No "amd" golden exists here: the plain file stands in, and the row says which and why.
  const std::string other = cls == "amd" ? "intel" : "amd";
  std::tie(rc, device, row) = row_with(other);
  EXPECT_EQ(device["golden_class"], other);
  EXPECT_EQ(row["golden_class"], "lavapipe") << row.dump(2);
  EXPECT_NE(row.dump().find("compared with the lavapipe golden (reference.low.exr"), std::string::npos) << row.dump(2);
  EXPECT_NE(row.dump().find("no " + other + " golden is approved"), std::string::npos) << row.dump(2);

  // An approved golden of that class is found and used (here a copy of this device's, so the
  // row still passes: the lookup, not the image, is under test).
  GoldenStore store(o.suite.goldens_dir, "tiny");
  fs::path plain = fs::path(store.dir()) / store.file_name("reference.low", cls);
  fs::copy_file(plain, fs::path(store.dir()) / store.file_name("reference.low", other));
  json meta = store.metadata();  // an approved golden has its record
  meta["files"][store.file_name("reference.low", other)] = meta["files"][store.file_name("reference.low", cls)];
  store.write_metadata(meta);
  std::tie(rc, device, row) = row_with(other);
  EXPECT_EQ(rc, 0) << row.dump(2);
  EXPECT_EQ(row["golden_class"], other);
  EXPECT_EQ(row.dump().find("compared with the"), std::string::npos) << row.dump(2);
}

// A run on a golden folder whose golden.json was deleted fails, naming golden.json and the
// file (the reference's spp, device and noise floor are gone); update-goldens, which reads the
// old files without their records, writes it again and the run passes.
TEST(GoldenRecords, RunWithoutGoldenJsonFailsNamingItAndReapprovalRestoresIt) {
  TempDir dir;
  fs::path cases = dir.path() / "cases";
  write_tiny_case(cases);
  UpdateOptions o = test::approve_goldens(cases, dir.path() / "goldens");
  SuiteOptions run = o.suite;
  run.out = (dir.path() / "out").string();
  run.stability_scan = false;
  ASSERT_EQ(cmd_run(run), 0);
  const fs::path meta = dir.path() / "goldens" / "tiny" / "golden.json";
  ASSERT_TRUE(fs::remove(meta));
  EXPECT_EQ(cmd_run(run), 1);
  json results = json::parse(read_text(fs::path(run.out) / "results.json"));
  ASSERT_EQ(results["case_errors"].size(), 1u) << results.dump(2);
  const std::string e = results["case_errors"][0];
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_EQ(e.rfind("tiny: " + meta.string() + ": expected the record of ", 0), 0u) << e;
  EXPECT_NE(e.find("got no file"), std::string::npos) << e;

  ASSERT_EQ(cmd_update_goldens(o), 0);
  ASSERT_TRUE(fs::exists(meta));
  EXPECT_EQ(cmd_run(run), 0);
}

TEST(UpdateGoldens, SppAndNoiseFloorNeedReference) {
  UpdateOptions o;
  o.reason = "test";
  o.spp = 64;
  EXPECT_THROW(cmd_update_goldens(o), std::invalid_argument);
  o.spp = 0;
  o.noise_floor = true;
  EXPECT_THROW(cmd_update_goldens(o), std::invalid_argument);
}

class SppSplit : public test::GpuTest {};

// Up to 512 spp the split is today's (at most 16 per frame: the committed references stay
// reproducible); above, about sqrt(spp) per frame.
TEST_F(SppSplit, SmallBudgetsUnchangedLargeOnesUseFewerFrames) {
  TempDir dir;
  write_tiny_case(dir.path() / "cases");
  Case c = load_case((dir.path() / "cases" / "tiny.json").string());
  TechniqueRun row;
  row.technique = "reference";
  row.presets = {"ultra"};
  for (auto [spp, frames] : std::vector<std::pair<uint32_t, uint32_t>>{{12, 1}, {24, 2}, {512, 32}, {600, 25}, {1024, 32}}) {
    c.reference_spp = spp;
    CaseRender r = render_reference(gpu(), c);
    EXPECT_EQ(r.spp, spp);
    EXPECT_EQ(r.frames, frames) << spp << " spp";
    // A reference row of the case renders its own spp, not the committed reference's budget.
    row.spp = 24;
    CaseRender rr = render_case(gpu(), c, row, "ultra");
    EXPECT_EQ(rr.spp, 24u);
    EXPECT_EQ(rr.frames, 2u);
  }
}

}  // namespace
}  // namespace gib
