// The GPU tier: case sizes per tier, the reference cache's key and its
// render-on-demand, half-float goldens that round exactly as their CPU mirror, approval from a
// finished run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/case.h"
#include "harness/image_io.h"
#include "harness/suite.h"
#include "harness/references.h"
#include "renderer/codecs/half.h"
#include "tests/temp_dir.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Writes `c` as DIR/cases/NAME.json and returns suite options on it (goldens, cache and output
// inside DIR; the stability scan off), at `tier`.
SuiteOptions tiny_suite(const test::TempDir& dir, const std::string& name, const json& c, const std::string& tier) {
  fs::create_directories(dir.path() / "cases");
  std::ofstream(dir.path() / "cases" / (name + ".json")) << c.dump(2);
  SuiteOptions o;
  o.cases_dir = (dir.path() / "cases").string();
  o.goldens_dir = (dir.path() / "goldens").string();
  o.reference_cache = (dir.path() / "cache").string();
  o.out = (dir.path() / "out").string();
  o.tier = tier;
  o.stability_scan = false;
  return o;
}

TEST(Tier, ChosenByDeviceClassOrForcedAndUnknownNamesAreRefused) {
  EXPECT_EQ(resolve_tier("", "lavapipe"), Tier::ci);
  EXPECT_EQ(resolve_tier("", "nvidia"), Tier::gpu);
  EXPECT_EQ(resolve_tier("", "amd"), Tier::gpu);
  EXPECT_EQ(resolve_tier("ci", "nvidia"), Tier::ci);
  EXPECT_EQ(resolve_tier("gpu", "lavapipe"), Tier::gpu);
  try {
    resolve_tier("big", "nvidia");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--tier: expected ci or gpu, got 'big'"), std::string::npos) << e.what();
  }
}

TEST(Tier, EveryCommittedCaseHasAGpuSizeOfTheSameAspect) {
  for (const Case& c : load_cases(std::string(GIB_SOURCE_DIR) + "/cases")) {
    SCOPED_TRACE(c.name);
    Case g = at_tier(c, Tier::gpu);
    EXPECT_EQ(g.width, c.gpu_width);
    EXPECT_GE(g.width * g.height, 640u * 360u) << "a GPU tier smaller than Falcor's image tests";
    EXPECT_NEAR(double(g.width) / g.height, double(c.width) / c.height, 0.02) << "ROIs are normalised: same aspect";
    Case ci = at_tier(c, Tier::ci);
    EXPECT_EQ(ci.width, c.width);
    EXPECT_FALSE(c.scene_text.empty());
  }
}

TEST(Tier, PixelCoordinateOptionsNameTheSamePointAtTheGpuSize) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/nan-injection.json");
  Case g = at_tier(c, Tier::gpu);
  ASSERT_FALSE(c.negative_controls.empty());
  for (size_t i = 0; i < c.negative_controls.size(); ++i) {
    const auto& was = c.negative_controls[i].run.options;
    const auto& now = g.negative_controls[i].run.options;
    if (!was.count("inject_x")) continue;
    // Pixel 34 of 128 (centre 34.5 / 128 = 0.2695) is pixel 172 of 640 (172.5 / 640 = 0.2695).
    EXPECT_DOUBLE_EQ(now.at("inject_x"), std::floor((was.at("inject_x") + 0.5) * g.width / c.width));
    EXPECT_DOUBLE_EQ(now.at("inject_y"), std::floor((was.at("inject_y") + 0.5) * g.height / c.height));
    EXPECT_EQ(now.at("inject_frame"), was.at("inject_frame")) << "not a pixel option";
  }
  EXPECT_EQ(at_tier(c, Tier::ci).negative_controls[0].run.options, c.negative_controls[0].run.options);
}

TEST(Tier, ReferenceKeyChangesWithWhatChangesTheReferenceAndNothingElse) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/cornell.json");
  c = at_tier(c, Tier::gpu);
  ReferenceRequest req{0.01, 4096};
  const std::string base = reference_key(reference_key_inputs(c, req));
  EXPECT_EQ(reference_key(reference_key_inputs(c, req)), base) << "deterministic";
  EXPECT_EQ(path_tracer_revision(), path_tracer_revision());
  auto differs = [&](const char* what, Case changed, ReferenceRequest r) {
    EXPECT_NE(reference_key(reference_key_inputs(changed, r)), base) << what;
  };
  Case s = c;
  s.scene_text += " ";
  differs("scene contents", s, req);
  s = c;
  s.scene.meshes[0].positions[0].x += 0.25f;  // what a glTF object's buffer holds: not in scene_text
  differs("imported geometry", s, req);
  s = c;
  s.width = 320;
  differs("size", s, req);
  s = c;
  s.reference_seed = 7;
  differs("seed", s, req);
  differs("spp", c, ReferenceRequest{0.01, 8192});
  differs("target floor", c, ReferenceRequest{0.005, 4096});
  s = c;
  s.output = "direct";
  differs("compared AOVs", s, req);
  // Not part of what the path tracer renders: the description, a technique's preset list, where
  // the scene file lives.
  s = c;
  s.description = "another description";
  s.scene_file = "/elsewhere/cornell.json";
  EXPECT_EQ(reference_key(reference_key_inputs(s, req)), base);
}

TEST(Tier, StartSppIsPredictedFromTheCommittedFloorAndTheTightestBound) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/cornell.json");
  json meta = {{"noise_floor", {{"flip", 0.002}, {"aovs", {{"radiance", 0.002}}}, {"spp", 65536}}}};
  ReferenceRequest r = reference_request(c, meta);
  // 65536 x (0.002 / 0.008)^2 = 4096: the power of two at or above.
  EXPECT_EQ(r.start_spp, 4096u);
  EXPECT_LE(r.target_floor, kReferenceNoiseFloorMax);
  // A floor measured on an AOV no run compares with does not raise it.
  meta["noise_floor"]["aovs"]["unused_aov"] = 0.5;
  EXPECT_EQ(reference_request(c, meta).start_spp, 4096u);
  // A whole-image flip bound of 0.015 vs the reference: the floor must be <= 0.005.
  for (auto& run : c.techniques) run.thresholds.push_back(Threshold{"flip", "reference", "", 0.015, std::nullopt});
  EXPECT_DOUBLE_EQ(reference_request(c, meta).target_floor, 0.005);
  EXPECT_EQ(reference_request(c, meta).start_spp, 16384u);  // 65536 x (0.002 / 0.004)^2
}

TEST(Tier, PilotThenTheSppItsFloorPredicts) {
  EXPECT_EQ(pilot_spp(256), 256u);
  EXPECT_EQ(pilot_spp(4096), 4096u);
  EXPECT_EQ(pilot_spp(262144), 4096u);
  EXPECT_EQ(pilot_spp(8192), 1024u);
  ReferenceRequest req{0.01, 262144};
  // Floor 0.0232 at 8192 spp: 8192 x (0.0232 / 0.009)^2 = 54,434 -> 57,344 (a multiple of 4096).
  EXPECT_EQ(next_spp(8192, 0.0232, req), 57344u);
  EXPECT_EQ(next_spp(8192, 0.0101, req), 16384u) << "at least twice what was rendered";
  req.max_spp = 32768;
  EXPECT_EQ(next_spp(8192, 0.0232, req), 32768u) << "never past the budget";
}

TEST(Tier, HalfGoldensStoreExactlyWhatTheirCpuMirrorRounds) {
  test::TempDir dir("gib_tier_half_");
  FloatImage img(7, 5, 4);
  for (size_t i = 0; i < img.pixels.size(); ++i)  // from half's denormals (1e-7) up to ~1.6e4
    img.pixels[i] = 1e-7f * std::pow(1.7f, float(i % 40)) * (1.0f + 0.013f * float(i));
  img.pixels[3] = -0.3333333f;
  ASSERT_TRUE(fits_half(img));
  std::string path = (dir.path() / "h.exr").string();
  write_exr(path, img, true);
  bool half = false;
  FloatImage back = read_image(path, &half);
  EXPECT_TRUE(half);
  FloatImage mirror = round_to_half(img);
  ASSERT_EQ(back.pixels.size(), mirror.pixels.size());
  for (size_t i = 0; i < back.pixels.size(); ++i)
    EXPECT_EQ(back.pixels[i], mirror.pixels[i]) << i << " of " << img.pixels[i];
  img.pixels[0] = 70000.0f;  // past half's range: such an image stays float
  EXPECT_FALSE(fits_half(img));
  FloatImage f32(2, 2, 4, 0.1f);
  write_exr(path, f32, false);
  read_image(path, &half);
  EXPECT_FALSE(half);
}

// A furnace case (a constant answer, so its reference converges at the first spp tried) at a
// 32x18 GPU tier: `references` renders it once into the cache and then finds it; `run --tier
// gpu` uses it; approval from that run writes half goldens that the next run matches exactly; a
// changed scene misses the cache and is rendered again.
TEST(Tier, GpuTierRendersReferencesOnceApprovesFromARunAndMatchesItsGoldens) {
  test::TempDir dir("gib_tier_");
  fs::path cases = dir.path() / "cases", goldens = dir.path() / "goldens", cache = dir.path() / "cache";
  fs::create_directories(cases);
  json c = json::parse(std::ifstream(std::string(GIB_SOURCE_DIR) + "/cases/white-furnace.json"));
  c.erase("$schema");
  // The reference's row only: the tier machinery is under test, not the other techniques'
  // accuracy at 32x18 (voxel-clipmap's 256-frame rows would add minutes and their own bounds).
  json rows = json::array();
  for (const json& t : c["techniques"])
    if (t["technique"] == "reference") rows.push_back(t);
  c["techniques"] = rows;
  c["scene"] = std::string(GIB_SOURCE_DIR) + "/cases/scenes/furnace.json";
  c["gpu_width"] = 32;
  c["gpu_height"] = 18;
  std::ofstream(cases / "furnace.json") << c.dump(2);
  SuiteOptions o;
  o.cases_dir = cases.string();
  o.goldens_dir = goldens.string();
  o.reference_cache = cache.string();
  o.tier = "gpu";
  o.stability_scan = false;
  ASSERT_EQ(cmd_references(o, false, false), 0);
  std::vector<fs::path> entries;
  for (auto& e : fs::directory_iterator(cache / "furnace")) entries.push_back(e.path());
  ASSERT_EQ(entries.size(), 1u);
  const fs::path entry = entries[0];
  ASSERT_TRUE(fs::exists(entry / "reference.exr"));
  FloatImage ref = read_image((entry / "reference.exr").string());
  EXPECT_EQ(ref.width, 32u);
  EXPECT_EQ(ref.height, 18u);
  const auto stamp = fs::last_write_time(entry / "reference.exr");
  ASSERT_EQ(cmd_references(o, false, false), 0);
  EXPECT_EQ(fs::last_write_time(entry / "reference.exr"), stamp) << "a cached reference is not rendered again";
  {  // An entry whose reference lost its record in golden.json cannot be read: it is rendered again.
    json meta = json::parse(std::ifstream(entry / "golden.json"));
    meta["files"].erase("reference.exr");
    std::ofstream(entry / "golden.json") << meta.dump(2);
  }
  ASSERT_EQ(cmd_references(o, false, false), 0);
  EXPECT_TRUE(json::parse(std::ifstream(entry / "golden.json"))["files"].contains("reference.exr"))
      << "the record is written again with the render";

  o.out = (dir.path() / "first").string();
  EXPECT_EQ(cmd_run(o), 1) << "no GPU-tier golden approved yet";
  json first = json::parse(std::ifstream(dir.path() / "first" / "results.json"));
  EXPECT_EQ(first["device"]["tier"], "gpu");
  EXPECT_EQ(first["references"]["furnace"]["rendered"], false);
  UpdateOptions up;
  up.suite = o;
  up.from_run = o.out;
  up.reason = "test";
  ASSERT_EQ(cmd_update_goldens(up), 0);
  bool half = false;
  read_image((goldens / "furnace" / "gpu" / "reference.ultra.exr").string(), &half);
  EXPECT_TRUE(half);
  EXPECT_FALSE(fs::exists(goldens / "furnace" / "reference.ultra.exr")) << "the CI tier's goldens are untouched";

  o.out = (dir.path() / "second").string();
  EXPECT_EQ(cmd_run(o), 0);
  json second = json::parse(std::ifstream(dir.path() / "second" / "results.json"));
  for (auto& r : second["results"])
    if (r["kind"] == "technique") {
      EXPECT_EQ(r["metrics"]["golden_differing_values"], 0.0) << r["technique"];
    }

  {  // A row the run did not render (the quick profile's not_run) is skipped and counted; a
     // selected row without its output is an error raised before any golden is replaced.
    const fs::path run = dir.path() / "second";
    json res = json::parse(std::ifstream(run / "results.json"));
    json row;
    for (auto& r : res["results"])
      if (r["kind"] == "technique") row = r;
    ASSERT_FALSE(row.is_null());
    json skipped = row;
    skipped["status"] = "not_run";
    skipped["image"] = "";
    res["results"].push_back(skipped);
    std::ofstream(run / "results.json") << res.dump();
    up.from_run = run.string();
    EXPECT_EQ(cmd_update_goldens(up), 0);
    const fs::path golden = goldens / "furnace" / "gpu" / "reference.ultra.exr";
    const auto stamp = fs::last_write_time(golden);
    json missing = row;
    missing["image"] = "no-such-row";
    res["results"].push_back(missing);
    std::ofstream(run / "results.json") << res.dump();
    EXPECT_THROW(cmd_update_goldens(up), std::runtime_error);
    EXPECT_EQ(fs::last_write_time(golden), stamp) << "nothing is replaced before the error";
  }

  c["description"] = "the same furnace, its scene inline and one value changed";
  json scene = json::parse(std::ifstream(std::string(GIB_SOURCE_DIR) + "/cases/scenes/furnace.json"));
  scene["frame_time"] = 0.02;
  c["scene"] = scene;
  std::ofstream(cases / "furnace.json") << c.dump(2);
  ASSERT_EQ(cmd_references(o, false, false), 0);
  size_t n = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(cache / "furnace")) ++n;
  EXPECT_EQ(n, 2u) << "another scene, another cache entry";

  // --reference at the GPU tier is refused (its references are not committed).
  up.from_run.clear();
  up.reference = true;
  EXPECT_THROW(cmd_update_goldens(up), std::invalid_argument);
}

// A budget (--max-spp) short of the floor keeps the reference, marked not converged; a run says
// so on its rows; a larger budget refines the entry.
TEST(Tier, BudgetedReferencesAreMarkedNotConvergedAndRefinedLater) {
  test::TempDir dir("gib_tier_budget_");
  fs::path cases = dir.path() / "cases";
  json c = {{"description", "a noisy tiny Cornell box"},
            {"scene", std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"},
            {"width", 16}, {"height", 9}, {"gpu_width", 16}, {"gpu_height", 9}, {"reference_spp", 4},
            {"techniques", {{{"technique", "direct"}, {"presets", {"low"}}}}}};
  SuiteOptions o = tiny_suite(dir, "noisy", c, "gpu");
  EXPECT_EQ(cmd_references(o, false, false, 4), 1) << "4 spp cannot reach a floor of 0.01";
  ReferenceSource src = reference_source(o.goldens_dir, o.reference_cache, at_tier(load_case((cases / "noisy.json").string()), Tier::gpu), Tier::gpu);
  ASSERT_TRUE(references_present(at_tier(load_case((cases / "noisy.json").string()), Tier::gpu), src));
  EXPECT_FALSE(references_converged(at_tier(load_case((cases / "noisy.json").string()), Tier::gpu), src));
  EXPECT_EQ(src.store.metadata()["noise_floor"]["spp"], 4);
  cmd_run(o);  // fails: no golden approved; the rows say the reference is short
  json r = json::parse(std::ifstream(dir.path() / "out" / "results.json"));
  EXPECT_EQ(r["references"]["noisy"]["converged"], false);
  bool said = false;
  for (auto& m : r["results"][0]["messages"]) said |= m.get<std::string>().find("reference not converged") == 0;
  EXPECT_TRUE(said) << r["results"][0]["messages"].dump();
  EXPECT_EQ(cmd_references(o, false, false, 16), 1);
  EXPECT_EQ(src.store.metadata()["noise_floor"]["spp"], 16) << "refined towards its floor's prediction, within the budget";
}

// not_caught_on: where a control's break is measured not to show, an uncaught control is
// "skipped" with the case's words; a caught one fails so the mark cannot go stale; elsewhere the
// usual rule holds.
TEST(Tier, NotCaughtOnMarksAControlPerClassAndTierAndCannotGoStale) {
  test::TempDir dir("gib_tier_nc_");
  fs::path cases = dir.path() / "cases";
  json c = {{"description", "tiny case for not_caught_on"},
            {"scene", std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"},
            {"width", 16}, {"height", 9}, {"reference_spp", 0}, {"analytic_value", 0.5},
            {"techniques", {{{"technique", "direct"}, {"presets", {"low"}},
                             {"thresholds", {{{"metric", "nan_count"}, {"max", 0}}}}}}},
            {"negative_controls",
             {{{"name", "uncaught"}, {"why", "passes everything"}, {"technique", "direct"}, {"presets", {"low"}},
               {"not_caught_on", {{"lavapipe@ci", "measured: no break here"}}},
               {"thresholds", {{{"metric", "nan_count"}, {"max", 0}}}}},
              {{"name", "caught"}, {"why", "fails its bound"}, {"technique", "direct"}, {"presets", {"low"}},
               {"not_caught_on", {{"lavapipe@ci", "stale mark"}}},
               {"thresholds", {{{"metric", "max_abs_error"}, {"against", "analytic"}, {"max", 0}}}}},
              {{"name", "elsewhere"}, {"why", "marked for another tier only"}, {"technique", "direct"},
               {"presets", {"low"}}, {"not_caught_on", {{"*@gpu", "only at the GPU tier"}}},
               {"thresholds", {{{"metric", "nan_count"}, {"max", 0}}}}}}}};
  SuiteOptions o = tiny_suite(dir, "nc", c, "ci");
  Case loaded = load_case((cases / "nc.json").string());
  EXPECT_EQ(loaded.negative_controls[0].not_caught_reason("lavapipe", "ci"), "measured: no break here");
  EXPECT_EQ(loaded.negative_controls[0].not_caught_reason("lavapipe", "gpu"), "");
  cmd_run(o);  // the technique row fails (no golden): only the controls are checked here
  json r = json::parse(std::ifstream(dir.path() / "out" / "results.json"));
  std::map<std::string, std::string> status;
  for (auto& row : r["results"])
    if (row["kind"] == "negative_control") status[row["negative_control"]] = row["status"];
  EXPECT_EQ(status["uncaught"], "skipped");
  EXPECT_EQ(status["caught"], "fail") << "a caught control marked not_caught_on is a stale mark";
  EXPECT_EQ(status["elsewhere"], "fail") << "an uncaught control without a mark for this class and tier fails";
  c["negative_controls"][0]["not_caught_on"] = {{"nvidia@big", "typo"}};
  std::ofstream(cases / "nc.json") << c.dump(2);
  try {
    load_case((cases / "nc.json").string());
    ADD_FAILURE() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("/negative_controls/0/not_caught_on/nvidia@big"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gib
