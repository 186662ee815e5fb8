// Scenario case loader: the real cases load, malformed cases fail with one line naming the file
// and the exact JSON pointer, technique options are validated, the schema matches the loader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "harness/case.h"
#include "tests/temp_dir.h"
#include "harness/suite.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"
#include "tests/technique_settings.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const std::string kCases = std::string(GIB_SOURCE_DIR) + "/cases";

// A fresh directory per test, removed afterwards.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("gib_case_") {}
};

// A small valid case with an inline scene; each malformed test breaks one thing in it.
json valid_case() {
  return json::parse(R"({
    "description": "test case",
    "scene": {
      "materials": {"white": {"albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"primitive": {"type": "box"}, "material": "white"}],
      "sky": {"type": "constant", "radiance": [1, 1, 1]}
    },
    "width": 64, "height": 36,
    "rois": [{"name": "centre", "box": [0.25, 0.25, 0.75, 0.75]}],
    "techniques": [
      {"technique": "direct", "presets": ["low", "medium"], "compare_aov": "direct",
       "thresholds": [{"metric": "flip", "max": 0.2}, {"metric": "roi_mean", "roi": "centre", "min": 0.1}]},
      {"technique": "reference", "thresholds": [{"metric": "flip", "against": "golden", "max": 0.05}]}
    ],
    "negative_controls": [
      {"name": "no-sky", "why": "no sky light", "technique": "direct", "options": {"sky_rays": 0},
       "thresholds": [{"metric": "flip", "max": 0.2}]}
    ]
  })");
}

std::string load_error(const std::string& path) {
  try {
    load_case(path);
  } catch (const CaseError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no error";
}

// Writes `doc` as <dir>/bad.json and checks the message is one line starting with
// "<file>: <pointer>: expected " and containing `also` (when given).
void expect_error(const TempDir& dir, const json& doc, const std::string& pointer, const std::string& also = "") {
  std::string file = dir.write("bad.json", doc.dump(2));
  std::string msg = load_error(file);
  SCOPED_TRACE(msg);
  EXPECT_EQ(msg.rfind(file + ": " + pointer + ": expected ", 0), 0u) << "pointer " << pointer;
  EXPECT_EQ(msg.find('\n'), std::string::npos);
  if (!also.empty()) {
    EXPECT_NE(msg.find(also), std::string::npos) << "missing: " << also;
  }
}

// ---------------------------------------------------------------- the real cases

TEST(CaseLoad, Cornell) {
  Case c = load_case(kCases + "/cornell.json");
  EXPECT_EQ(c.name, "cornell");
  EXPECT_EQ(fs::path(c.scene_file), fs::path(kCases + "/scenes/cornell.json").lexically_normal());
  EXPECT_FALSE(c.scene.instances.empty());
  EXPECT_EQ(c.width, 128u);
  EXPECT_EQ(c.height, 72u);
  EXPECT_FALSE(c.description.empty());
  ASSERT_EQ(c.techniques.size(), 3u);
  const TechniqueRun& direct = c.techniques[0];
  EXPECT_EQ(direct.technique, "direct");
  EXPECT_EQ(direct.compare_aov, "direct");
  // Same light paths as the reference's direct AOV: the image mean within [0.95, 1.05].
  std::optional<double> all_min, all_max;
  for (const Threshold& t : direct.thresholds)
    if (t.metric == "roi_ratio" && t.against == "reference" && t.roi == "all") all_min = t.min, all_max = t.max;
  ASSERT_TRUE(all_min && all_max);
  EXPECT_EQ(*all_min, 0.95);
  EXPECT_EQ(*all_max, 1.05);
  // deferred lights the same paths with the same code: the same bounds.
  EXPECT_EQ(c.techniques[1].technique, "deferred");
  EXPECT_EQ(c.techniques[1].thresholds.size(), direct.thresholds.size());
  EXPECT_EQ(c.techniques[2].technique, "reference");
  ASSERT_FALSE(c.techniques[2].thresholds.empty());
  EXPECT_EQ(c.techniques[2].thresholds[0].against, "reference");
  EXPECT_EQ(c.techniques[2].spp, 256u);

  ASSERT_EQ(c.negative_controls.size(), 2u);
  EXPECT_EQ(c.negative_controls[1].run.technique, "deferred");
  const TechniqueRun& nc = c.negative_controls[0].run;
  EXPECT_EQ(nc.technique, "direct");
  ASSERT_EQ(nc.presets.size(), 1u);
  EXPECT_EQ(nc.compare_aov, "radiance");
  EXPECT_EQ(nc.options.at("sky_rays"), 0.0);
  ASSERT_FALSE(nc.thresholds.empty());
  EXPECT_EQ(nc.thresholds[0].metric, "roi_ratio");
  EXPECT_EQ(nc.thresholds[0].roi, "all");
  EXPECT_EQ(nc.thresholds[0].min, all_min) << "the control must be held to the positive's bound";
  EXPECT_EQ(nc.thresholds[0].max, all_max);
  Settings s = apply_options(find_technique(nc.technique), apply_preset(find_technique("direct"), nc.presets[0], {}),
                             nc.options);
  EXPECT_EQ(sky_rays(s), 0u);
}

TEST(CaseLoad, WhiteFurnace) {
  Case c = load_case(kCases + "/white-furnace.json");
  EXPECT_EQ(c.name, "white-furnace");
  EXPECT_EQ(c.width, 96u);
  EXPECT_EQ(c.height, 54u);
  EXPECT_EQ(c.reference_spp, 65536u);
  ASSERT_TRUE(c.analytic_value);
  EXPECT_EQ(*c.analytic_value, 1.0);
  // The reference's row, then voxel-clipmap's (per-pixel sky rays, and sky through its clipmap),
  // which converge over frames: held to the analytic value in both ROIs; then gow-ragnarok's
  // (one frame: SSGI must add no energy), held to the same band; then voxel-clipmap's
  // no-geometry-light row, held to it too.
  ASSERT_EQ(c.techniques.size(), 5u);
  EXPECT_EQ(c.techniques[3].technique, "gow-ragnarok");
  EXPECT_EQ(c.techniques[3].thresholds[0].against, "analytic");
  EXPECT_EQ(c.techniques[4].options.at("geometry_light"), 0.0);
  for (size_t i : {1u, 2u, 4u}) {
    EXPECT_EQ(c.techniques[i].technique, "voxel-clipmap");
    EXPECT_EQ(c.techniques[i].frames, 256u);
    ASSERT_GE(c.techniques[i].thresholds.size(), 2u);
    EXPECT_EQ(c.techniques[i].thresholds[0].against, "analytic");
  }
  EXPECT_EQ(c.techniques[2].options.at("sky_rays"), 0.0);
  const TechniqueRun& ref = c.techniques[0];
  EXPECT_EQ(ref.technique, "reference");
  EXPECT_EQ(ref.presets, std::vector<std::string>{"ultra"});
  ASSERT_FALSE(ref.thresholds.empty());
  EXPECT_EQ(ref.thresholds[0].metric, "max_abs_error");
  EXPECT_EQ(ref.thresholds[0].against, "analytic");
  EXPECT_EQ(ref.thresholds[0].max, 0.01);
  for (const Threshold& t : ref.thresholds) {
    if (!t.roi.empty()) {
      EXPECT_TRUE(std::any_of(c.rois.begin(), c.rois.end(), [&](const Roi& r) { return r.name == t.roi; }));
    }
    if (t.metric == "nan_count") {
      EXPECT_EQ(t.against, "");
    }
  }
  ASSERT_EQ(c.negative_controls.size(), 1u);
  const TechniqueRun& nc = c.negative_controls[0].run;
  EXPECT_EQ(nc.options.at("max_bounces"), 1.0);
  ASSERT_EQ(nc.thresholds.size(), 1u);
  EXPECT_EQ(nc.thresholds[0].metric, "max_abs_error");
  EXPECT_EQ(nc.thresholds[0].max, 0.01);
  const Technique& t = find_technique("reference");
  EXPECT_EQ(apply_options(t, apply_preset(t, "ultra", {}), nc.options).params<ReferenceSettings>().max_bounces, 1u);
}

TEST(CaseLoad, DefaultsAndInlineScene) {
  TempDir dir;
  json doc = valid_case();
  doc.erase("width");
  doc.erase("height");
  Case c = load_case(dir.write("inline-ok.json", doc.dump()));
  EXPECT_EQ(c.name, "inline-ok");
  EXPECT_EQ(c.scene_file, "");
  EXPECT_EQ(c.scene.instances.size(), 1u);
  EXPECT_EQ(c.width, 256u);
  EXPECT_EQ(c.height, 144u);
  EXPECT_EQ(c.frames, 1u);
  EXPECT_EQ(c.output, "radiance");
  EXPECT_EQ(c.flip_mode, "hdr");
  EXPECT_EQ(c.techniques[1].presets, std::vector<std::string>{"medium"});
  EXPECT_EQ(c.techniques[1].thresholds[0].against, "golden");
  EXPECT_EQ(c.techniques[0].thresholds[0].against, "reference");
  EXPECT_EQ(c.techniques[0].thresholds[1].against, "") << "roi_mean measures the output alone";
  EXPECT_EQ(c.negative_controls[0].run.presets, std::vector<std::string>{"medium"});
  ASSERT_EQ(c.rois.size(), 1u);
  EXPECT_FLOAT_EQ(c.rois[0].x1, 0.75f);
}

// ---------------------------------------------------------------- malformed cases

TEST(CaseErrors, TopLevelFields) {
  TempDir dir;
  auto with = [](const std::string& key, const json& v) {
    json d = valid_case();
    d[key] = v;
    return d;
  };
  expect_error(dir, with("width", 0), "/width", "integer in [1, 8192], got 0");
  expect_error(dir, with("width", 8193), "/width");
  expect_error(dir, with("height", "144"), "/height", "got \"144\"");
  expect_error(dir, with("height", 36.5), "/height");
  expect_error(dir, with("frames", 0), "/frames");
  expect_error(dir, with("flip_mode", "sdr"), "/flip_mode", "hdr, ldr");
  expect_error(dir, with("ppd", 0), "/ppd", "number > 0");
  expect_error(dir, with("golden_flip_max", 2), "/golden_flip_max");
  expect_error(dir, with("output", "final"), "/output", "radiance, direct, indirect_diffuse");
  expect_error(dir, with("reference_spp", -1), "/reference_spp");
  expect_error(dir, with("description", ""), "/description");
  expect_error(dir, with("widht", 64), "/widht", "unknown key \"widht\"");
  expect_error(dir, with("a/b~c", 1), "/a~1b~0c");
  json d = valid_case();
  d.erase("description");
  expect_error(dir, d, "/description", "got missing key");
  d = valid_case();
  d.erase("techniques");
  expect_error(dir, d, "/techniques", "got missing key");
  expect_error(dir, with("techniques", json::array()), "/techniques", "non-empty array");
  expect_error(dir, json::array(), "/", "got empty array");
}

TEST(CaseErrors, UnknownKeyListsAllowedKeys) {
  TempDir dir;
  json d = valid_case();
  d["techniques"][0]["thresholds"][0]["maxx"] = 1;
  expect_error(dir, d, "/techniques/0/thresholds/0/maxx", "one of the keys metric, against, roi, max, min");
}

TEST(CaseErrors, TechniquesPresetsOptions) {
  TempDir dir;
  json d = valid_case();
  d["techniques"][0]["technique"] = "radiance-cash";
  expect_error(dir, d, "/techniques/0/technique", "direct, reference");
  d = valid_case();
  d["techniques"][0]["presets"] = {"low", "extreme"};
  expect_error(dir, d, "/techniques/0/presets/1", "low, medium, high, ultra");
  d = valid_case();
  d["techniques"][0]["presets"] = {"low", "low"};
  expect_error(dir, d, "/techniques/0/presets/1", "\"low\" again");
  d = valid_case();
  d["techniques"][0]["presets"] = json::array();
  expect_error(dir, d, "/techniques/0/presets", "non-empty array");
  d = valid_case();
  d["techniques"][0]["options"] = {{"sky_rayz", 1}};
  // The list: the technique's own options first, then the options every technique shares.
  expect_error(dir, d, "/techniques/0/options/sky_rayz", "(sky_rays, nan_guards, ");
  expect_error(dir, d, "/techniques/0/options/sky_rayz", "), got unknown option \"sky_rayz\"");
  d = valid_case();
  d["techniques"][0]["options"] = {{"sky_rays", -1}};
  expect_error(dir, d, "/techniques/0/options/sky_rays", "integer in [0, 4294967295], got -1");
  d = valid_case();
  d["techniques"][0]["options"] = {{"sky_rays", true}};
  expect_error(dir, d, "/techniques/0/options/sky_rays", "got true");
  d = valid_case();
  d["techniques"][1]["options"] = {{"max_bounces", 0}};
  expect_error(dir, d, "/techniques/1/options/max_bounces", "integer in [1, ");
  d = valid_case();
  d["techniques"][1]["options"] = {{"sky_rays", 4}};  // a direct option on the reference
  expect_error(dir, d, "/techniques/1/options/sky_rays", "max_bounces, spp_per_frame");
  d = valid_case();
  d["techniques"][0]["compare_aov"] = "gbuffer_albedo";
  expect_error(dir, d, "/techniques/0/compare_aov", "radiance, direct, indirect_diffuse");
  d = valid_case();
  d["techniques"].push_back({{"technique", "direct"}, {"presets", {"high", "medium"}}});
  expect_error(dir, d, "/techniques/2/presets/1", "/techniques/0");
}

// A label tells apart runs of one technique and preset with other options (alpha-foliage's
// strategies): rows, images and goldens are named TECHNIQUE+LABEL; a repeated technique+label
// and preset, a malformed label or one on a negative control is an error naming the field.
TEST(CaseLoad, RowFramesOverrideTheCaseFramesWhereAllowed) {
  TempDir dir;
  json d = valid_case();
  d["techniques"][0]["frames"] = 12;
  Case c = load_case(dir.write("frames.json", d.dump()));
  EXPECT_EQ(c.techniques[0].frames, 12u);
  EXPECT_EQ(c.techniques[1].frames, 0u);  // the case's
  d = valid_case();
  d["techniques"][1]["frames"] = 8;  // the reference has spp instead
  expect_error(dir, d, "/techniques/1/frames", "no \"frames\" in a reference");
  d = valid_case();
  d["techniques"][0]["frames"] = 0;
  expect_error(dir, d, "/techniques/0/frames");
  d = valid_case();
  d["frames"] = 4;
  d["eval_frames"] = {2, 4};
  d["techniques"][0]["frames"] = 8;
  expect_error(dir, d, "/techniques/0/frames", "evaluated per frame");
}

TEST(CaseLoad, LabelsTellRunsOfOneTechniqueAndPresetApart) {
  TempDir dir;
  json d = valid_case();
  json run = d["techniques"][0];
  run["label"] = "limit2";
  run["options"] = {{"alpha_any_hit_limit", 2}};
  d["techniques"].push_back(run);
  Case c = load_case(dir.write("labels.json", d.dump()));
  ASSERT_EQ(c.techniques.size(), 3u);
  EXPECT_EQ(c.techniques[0].name(), c.techniques[0].technique);
  EXPECT_EQ(c.techniques[2].name(), c.techniques[2].technique + "+limit2");
  EXPECT_EQ(c.techniques[2].options.at("alpha_any_hit_limit"), 2.0);

  json again = d;
  again["techniques"].push_back(run);
  expect_error(dir, again, "/techniques/3/presets/0", "+limit2");
  for (const json& bad : {json(""), json("Limit2"), json("a b"), json(7), json(std::string(33, 'a'))}) {
    json e = valid_case();
    e["techniques"][0]["label"] = bad;
    expect_error(dir, e, "/techniques/0/label", "a-z, 0-9");
  }
  json nc = valid_case();
  nc["negative_controls"][0]["label"] = "x";
  expect_error(dir, nc, "/negative_controls/0/label", "no label in a negative control");
}

TEST(CaseLoad, AttributeFlagsARowOfATechniqueWithStageOracles) {
  TempDir dir;
  json d = valid_case();
  json run = {{"technique", "probe-volume"}, {"compare_aov", "indirect_diffuse"}, {"attribute", true}};
  d["techniques"].push_back(run);
  Case c = load_case(dir.write("attribute.json", d.dump()));
  EXPECT_TRUE(c.techniques[2].attribute);
  EXPECT_FALSE(c.techniques[0].attribute);
  json e = valid_case();
  e["techniques"][0]["attribute"] = true;  // direct declares no stage oracles
  expect_error(dir, e, "/techniques/0/attribute", "a technique with stage oracles (direct declares none)");
  e = d;
  e["techniques"][2]["attribute"] = "yes";
  expect_error(dir, e, "/techniques/2/attribute", "true or false");
  e = valid_case();
  e["negative_controls"][0]["attribute"] = false;
  expect_error(dir, e, "/negative_controls/0/attribute", "no \"attribute\" in a negative control");
}

TEST(CaseLoad, KnownFailureEverywhereOrPerDeviceClass) {
  TempDir dir;
  json d = valid_case();
  d["techniques"][0]["known_failure"] = "loses light (issue 19)";
  Case c = load_case(dir.write("kf.json", d.dump()));
  EXPECT_EQ(c.techniques[0].known_failure_on("lavapipe"), "loses light (issue 19)");
  EXPECT_EQ(c.techniques[0].known_failure_on("nvidia"), "loses light (issue 19)");
  EXPECT_EQ(c.techniques[1].known_failure_on("nvidia"), "") << "an unmarked run";
  d["techniques"][0]["known_failure"] = {{"nvidia", "leaks on NVIDIA only"}};
  c = load_case(dir.write("kf.json", d.dump()));
  EXPECT_EQ(c.techniques[0].known_failure_on("nvidia"), "leaks on NVIDIA only");
  EXPECT_EQ(c.techniques[0].known_failure_on("lavapipe"), "") << "not marked on the other classes";
  // Per tier: CLASS@TIER, then *@TIER, then CLASS, then *.
  d["techniques"][0]["known_failure"] = {{"nvidia@gpu", "a 640x360 ROI"}, {"*@ci", "a 128x72 ROI"}, {"nvidia", "NVIDIA"}};
  c = load_case(dir.write("kf.json", d.dump()));
  EXPECT_EQ(c.techniques[0].known_failure_on("nvidia", "gpu"), "a 640x360 ROI");
  EXPECT_EQ(c.techniques[0].known_failure_on("nvidia", "ci"), "a 128x72 ROI");
  EXPECT_EQ(c.techniques[0].known_failure_on("lavapipe", "ci"), "a 128x72 ROI");
  EXPECT_EQ(c.techniques[0].known_failure_on("lavapipe", "gpu"), "");
  EXPECT_EQ(c.techniques[0].known_failure_on("amd", "ci"), "a 128x72 ROI");
  d["techniques"][0]["known_failure"] = {{"nvidia@big", "typo"}};
  expect_error(dir, d, "/techniques/0/known_failure/nvidia@big", "nvidia@gpu");

  d["techniques"][0]["known_failure"] = "";
  expect_error(dir, d, "/techniques/0/known_failure", "non-empty string, or an object of device class");
  d["techniques"][0]["known_failure"] = json::object();
  expect_error(dir, d, "/techniques/0/known_failure", "at least one key");
  d["techniques"][0]["known_failure"] = {{"nvdia", "typo"}};
  expect_error(dir, d, "/techniques/0/known_failure/nvdia", "lavapipe, nvidia, amd, intel, other");
  d["techniques"][0]["known_failure"] = {{"nvidia", ""}};
  expect_error(dir, d, "/techniques/0/known_failure/nvidia", "non-empty string");
  d["techniques"][0]["known_failure"] = 3;
  expect_error(dir, d, "/techniques/0/known_failure", "got 3");
}

TEST(CaseErrors, Thresholds) {
  TempDir dir;
  auto with_threshold = [](const json& t) {
    json d = valid_case();
    d["techniques"][0]["thresholds"][0] = t;
    return d;
  };
  const std::string p = "/techniques/0/thresholds/0";
  expect_error(dir, with_threshold({{"metric", "flip"}}), p, "\"max\" or \"min\" (or both), got neither");
  expect_error(dir, with_threshold({{"metric", "ssim"}, {"max", 1}}), p + "/metric", "flip, psnr, relmse");
  expect_error(dir, with_threshold({{"metric", "flip"}, {"against", "golde"}, {"max", 1}}), p + "/against",
               "reference, golden, analytic");
  expect_error(dir, with_threshold({{"metric", "flip"}, {"against", "analytic"}, {"max", 1}}), p + "/against",
               "analytic_value");
  expect_error(dir, with_threshold({{"metric", "roi_mean"}, {"against", "reference"}, {"min", 1}}), p + "/against");
  expect_error(dir, with_threshold({{"metric", "flip"}, {"roi", "nowhere"}, {"max", 1}}), p + "/roi",
               "(centre), got \"nowhere\"");
  expect_error(dir, with_threshold({{"metric", "psnr"}, {"min", 30}, {"max", 20}}), p + "/min", "<= max (20)");
  expect_error(dir, with_threshold({{"metric", "psnr"}, {"min", "30"}}), p + "/min");
  json d = valid_case();
  d["techniques"][0]["thresholds"] = json::object();
  expect_error(dir, d, "/techniques/0/thresholds", "got empty object");
  // With an analytic value the same threshold is fine.
  d = with_threshold({{"metric", "max_abs_error"}, {"against", "analytic"}, {"max", 0.1}});
  d["analytic_value"] = 1.0;
  EXPECT_NO_THROW(load_case(dir.write("analytic-ok.json", d.dump())));
}

TEST(CaseErrors, Rois) {
  TempDir dir;
  json d = valid_case();
  d["rois"][0]["box"] = {0.5, 0.2, 0.5, 0.8};
  expect_error(dir, d, "/rois/0/box", "x0 < x1 and y0 < y1, got [0.5, 0.2, 0.5, 0.8]");
  d = valid_case();
  d["rois"][0]["box"] = {0.1, 0.2, 1.5, 0.8};
  expect_error(dir, d, "/rois/0/box/2", "number in [0, 1], got 1.5");
  d = valid_case();
  d["rois"][0]["box"] = {0.1, 0.2, 0.3};
  expect_error(dir, d, "/rois/0/box", "got array of 3 elements");
  d = valid_case();
  d["rois"].push_back({{"name", "centre"}, {"box", {0, 0, 1, 1}}});
  expect_error(dir, d, "/rois/1/name", "\"centre\" again");
  d = valid_case();
  d["rois"][0]["name"] = "Centre Box";
  expect_error(dir, d, "/rois/0/name");
}

TEST(CaseErrors, NegativeControls) {
  TempDir dir;
  json d = valid_case();
  d["negative_controls"][0]["presets"] = {"low", "high"};
  expect_error(dir, d, "/negative_controls/0/presets", "exactly one preset");
  d = valid_case();
  d["negative_controls"][0].erase("thresholds");
  expect_error(dir, d, "/negative_controls/0/thresholds", "got missing key");
  d = valid_case();
  d["negative_controls"][0]["thresholds"] = json::array();
  expect_error(dir, d, "/negative_controls/0/thresholds", "non-empty array, got empty array");
  d = valid_case();
  d["negative_controls"][0].erase("why");
  expect_error(dir, d, "/negative_controls/0/why");
  d = valid_case();
  d["negative_controls"].push_back(d["negative_controls"][0]);
  expect_error(dir, d, "/negative_controls/1/name", "\"no-sky\" again");
  d = valid_case();
  d["negative_controls"][0]["options"] = {{"sky_rays", 0.5}};
  expect_error(dir, d, "/negative_controls/0/options/sky_rays", "got 0.5");
  d = valid_case();
  d["negative_controls"][0]["thresholds"][0]["roi"] = "room";
  expect_error(dir, d, "/negative_controls/0/thresholds/0/roi");
}

TEST(CaseErrors, Scenes) {
  TempDir dir;
  json d = valid_case();
  d["scene"]["objects"][0]["material"] = "whit";
  expect_error(dir, d, "/scene/objects/0/material", "got \"whit\"");
  d = valid_case();
  d["scene"] = json::object();
  expect_error(dir, d, "/scene/objects");
  d = valid_case();
  d["scene"]["sky"]["radiance"] = {1, 1};
  expect_error(dir, d, "/scene/sky/radiance");
  d = valid_case();
  d["scene"] = 5;
  expect_error(dir, d, "/scene", "got 5");
  d = valid_case();
  d["scene"] = "scenes/missing.json";
  expect_error(dir, d, "/scene", "\"scenes/missing.json\"");
  // A scene file with an error: the case pointer, then the scene file's own message.
  fs::create_directories(fs::path(dir.str()) / "scenes");
  std::string scene = dir.write("scenes/broken.json",
                                R"({"materials": {"w": {}}, "objects": [{"primitive": {"type": "cone"}, "material": "w"}]})");
  d["scene"] = "scenes/broken.json";
  expect_error(dir, d, "/scene", fs::path(scene).lexically_normal().string() + ": /objects/0/primitive/type");
  // The same file, fixed, loads relative to the case file's folder.
  dir.write("scenes/ok.json", R"({"materials": {"w": {}}, "objects": [{"primitive": {"type": "box"}, "material": "w"}]})");
  d["scene"] = "scenes/ok.json";
  Case c = load_case(dir.write("file-scene.json", d.dump()));
  EXPECT_EQ(c.scene_file, (fs::path(dir.str()) / "scenes/ok.json").lexically_normal().string());
}

TEST(CaseErrors, FileLevel) {
  TempDir dir;
  std::string file = dir.write("syntax.json", "{\n  \"width\": 64,\n  \"height\": ,\n}\n");
  std::string msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": line 3, column 13: expected valid JSON, got ", 0), 0u) << msg;

  file = dir.write("dup.json", R"({"description": "x", "techniques": [{"technique": "direct",
      "thresholds": [{"metric": "flip", "max": 0.1, "max": 0.5}]}]})");
  msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": /techniques/0/thresholds/0/max: expected each key once per object", 0), 0u) << msg;

  file = dir.write("huge.json", R"({"width": 1e999})");
  msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": expected valid JSON", 0), 0u) << msg;

  file = dir.write("empty.json", "");
  msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": line 1, column 1: expected valid JSON", 0), 0u) << msg;

  file = dir.write("Bad_Name.json", valid_case().dump());
  msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": expected a file name (the case name)", 0), 0u) << msg;

  msg = load_error(dir.str() + "/absent.json");
  EXPECT_EQ(msg.rfind(dir.str() + "/absent.json: expected a readable file", 0), 0u) << msg;
  msg = load_error(dir.str());
  EXPECT_EQ(msg.rfind(dir.str() + ": expected a case file, got a directory", 0), 0u) << msg;

  // Bytes that are not UTF-8 never reach the message raw.
  file = dir.write("binary.json", std::string("{\"description\": \"\xff\xfe\"}"));
  msg = load_error(file);
  EXPECT_EQ(msg.rfind(file + ": line 1", 0), 0u) << msg;
  for (char ch : msg) EXPECT_TRUE(ch >= 0x20 && ch < 0x7f) << msg;
}

// ---------------------------------------------------------------- technique options

// A pass reads its technique's settings typed; the wrong technique (or none) is one clear error.
TEST(TechniqueSettings, WrongOrMissingSettingsNameBothTypes) {
  auto message = [](const Settings& s) -> std::string {
    try {
      (void)s.params<RadianceCacheSettings>();
    } catch (const GraphError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message(Settings{}),
            "settings: a pass expected RadianceCacheSettings, but the technique settings are not set (no technique)");
  EXPECT_EQ(message(defaults_of("reference")),
            "settings: a pass expected RadianceCacheSettings, but the technique settings are ReferenceSettings");
  EXPECT_EQ(message(defaults_of("radiance-cache")), "no error");
  // Copies own their settings: changing one leaves the other.
  Settings a = defaults_of("radiance-cache");
  Settings b = a;
  rc(b).cascades = 7;
  EXPECT_NE(rc(a).cascades, 7u);
  // Every technique's presets and options apply to its own struct.
  for (const Technique& t : techniques())
    for (const std::string& p : t.presets) {
      Settings s = apply_preset(t, p, {});
      EXPECT_EQ(s.technique, t.name);
      for (const TechniqueOption& o : t.options) EXPECT_NO_THROW(apply_options(t, s, {{o.name, o.min}})) << o.name;
    }
}

TEST(CaseOptions, ApplyOptions) {
  const Technique& direct = find_technique("direct");
  const Technique& reference = find_technique("reference");
  Settings base = apply_preset(direct, "medium", {});
  base.width = 77;
  EXPECT_EQ(sky_rays(apply_options(direct, base, {{"sky_rays", 0}})), 0u);
  EXPECT_EQ(sky_rays(apply_options(direct, base, {})), sky_rays(base));
  // Another technique's options: its own settings struct (defaults + options), common settings kept.
  Settings r = apply_options(reference, base, {{"max_bounces", 1}, {"spp_per_frame", 16}});
  EXPECT_EQ(r.params<ReferenceSettings>().max_bounces, 1u);
  EXPECT_EQ(r.params<ReferenceSettings>().spp_per_frame, 16u);
  EXPECT_EQ(r.width, 77u);
  EXPECT_FALSE(r.has_params<DirectLightingParams>());  // the reference runs no direct_lighting

  auto message = [](const Technique& t, const std::map<std::string, double>& o) -> std::string {
    try {
      apply_options(t, Settings{}, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  std::string m = message(direct, {{"sky_rayz", 1}});
  EXPECT_NE(m.find("\"sky_rayz\""), std::string::npos) << m;
  EXPECT_NE(m.find("(sky_rays, nan_guards, inject_nan, inject_frame, inject_x, inject_y"), std::string::npos) << m;
  m = message(reference, {{"sky_rays", 1}});
  EXPECT_NE(m.find("max_bounces, spp_per_frame"), std::string::npos) << m;
  EXPECT_NE(message(reference, {{"max_bounces", 0}}).find("integer in [1, 4294967295], got 0"), std::string::npos);
  EXPECT_NE(message(reference, {{"spp_per_frame", 0}}).find("\"spp_per_frame\""), std::string::npos);
  EXPECT_NE(message(direct, {{"sky_rays", 1.5}}).find("got 1.5"), std::string::npos);
  EXPECT_NE(message(direct, {{"sky_rays", -1}}).find("got -1"), std::string::npos);
  EXPECT_NE(message(direct, {{"sky_rays", 4294967296.0}}).find("got 4294967296"), std::string::npos);
  EXPECT_NE(message(direct, {{"sky_rays", std::numeric_limits<double>::quiet_NaN()}}).find("got NaN"),
            std::string::npos);
  EXPECT_EQ(check_option(direct, "sky_rays", 64), "");
  // Their own options (1 and 3), then the same shared ones (nan_guards, inject_*, ...).
  EXPECT_EQ(technique_options(direct)[0].name, "sky_rays");
  EXPECT_EQ(technique_options(reference)[1].name, "spp_per_frame");
  EXPECT_EQ(technique_options(direct)[1].name, "nan_guards");
  // direct also has the direct-light modes' options (direct_light_modes.h), after the shared ones.
  const size_t modes = direct_light_options().size();
  EXPECT_EQ(technique_options(direct)[technique_options(direct).size() - modes].name, "direct_light");
  EXPECT_EQ(technique_options(direct).size() - modes + 2, technique_options(reference).size());
}

// ---------------------------------------------------------------- directories

TEST(CaseDir, LoadsSortedSkipsSchemaAndOtherFiles) {
  TempDir dir;
  json d = valid_case();
  dir.write("b-case.json", d.dump());
  dir.write("a-case.json", d.dump());
  dir.write("case.schema.json", R"({"type": "object"})");
  dir.write("notes.txt", "not a case");
  fs::create_directories(fs::path(dir.str()) / "scenes.json");  // a directory, not a file
  std::vector<Case> cases = load_cases(dir.str());
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].name, "a-case");
  EXPECT_EQ(cases[1].name, "b-case");

  d["width"] = 0;
  std::string bad = dir.write("c-case.json", d.dump());
  try {
    load_cases(dir.str());
    FAIL() << "a bad case in the directory must fail";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ": /width: expected", 0), 0u) << e.what();
  }
}

TEST(CaseDir, EmptyOrMissingDirectoryFails) {
  TempDir dir;
  EXPECT_THROW(load_cases(dir.str()), CaseError);
  EXPECT_THROW(load_cases(dir.str() + "/nope"), CaseError);
}

TEST(CaseDir, RealCasesLoad) {
  std::vector<Case> cases = load_cases(kCases);
  std::set<std::string> names;
  for (const Case& c : cases) names.insert(c.name);
  EXPECT_TRUE(names.count("cornell"));
  EXPECT_TRUE(names.count("white-furnace"));
}

// ---------------------------------------------------------------- schema

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

// A light structural check (no JSON-Schema validator): every case's top-level keys are
// declared by the schema and its required keys are present.
TEST(CaseSchema, CaseFilesUseOnlySchemaKeys) {
  json schema = read_json(kCases + "/case.schema.json");
  ASSERT_TRUE(schema["properties"].is_object());
  ASSERT_TRUE(schema["required"].is_array());
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(kCases)) {
    std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.ends_with(".schema.json")) continue;
    SCOPED_TRACE(name);
    json doc = read_json(entry.path().string());
    ASSERT_TRUE(doc.is_object());
    EXPECT_EQ(doc.value("$schema", ""), "./case.schema.json");
    for (auto it = doc.begin(); it != doc.end(); ++it)
      EXPECT_TRUE(schema["properties"].contains(it.key())) << "key not in the schema: " << it.key();
    for (const auto& r : schema["required"]) EXPECT_TRUE(doc.contains(r.get<std::string>())) << "missing " << r;
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

// The schema and the loader agree on the top-level keys and the metric names.
TEST(CaseSchema, SchemaMatchesLoader) {
  json schema = read_json(kCases + "/case.schema.json");
  TempDir dir;
  json d = valid_case();
  d["zzz"] = 1;
  std::string msg = load_error(dir.write("keys.json", d.dump()));
  std::string marker = "expected one of the keys ";
  auto at = msg.find(marker);
  ASSERT_NE(at, std::string::npos) << msg;
  std::string list = msg.substr(at + marker.size(), msg.find(", got") - at - marker.size());
  std::set<std::string> loader_keys;
  for (size_t start = 0; start <= list.size();) {
    size_t end = list.find(", ", start);
    if (end == std::string::npos) end = list.size();
    loader_keys.insert(list.substr(start, end - start));
    start = end + 2;
  }
  std::set<std::string> schema_keys;
  for (auto it = schema["properties"].begin(); it != schema["properties"].end(); ++it) schema_keys.insert(it.key());
  EXPECT_EQ(loader_keys, schema_keys);

  std::vector<std::string> schema_metrics = schema["$defs"]["threshold"]["properties"]["metric"]["anyOf"][0]["enum"];
  EXPECT_EQ(schema_metrics, case_metrics());
}

// stat_<name> thresholds name a counter the run's technique declares (Technique::stats).
TEST(CaseLoad, StatMetricsNameADeclaredCounter) {
  TempDir dir;
  json d = valid_case();
  d["techniques"][0]["technique"] = "deferred";
  d["techniques"][0]["thresholds"] = json::parse(R"([{"metric": "stat_vrcs_lit", "max": 0.7}])");
  EXPECT_EQ(load_error(dir.write("ok.json", d.dump())), "no error");
  d["techniques"][0]["thresholds"][0]["metric"] = "stat_nope";
  std::string msg = load_error(dir.write("unknown.json", d.dump()));
  EXPECT_NE(msg.find("unknown.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("stat_vrcs_lit"), std::string::npos) << "lists the known counters: " << msg;
  EXPECT_NE(msg.find("stat_nope"), std::string::npos) << msg;
  // direct declares no counters.
  d = valid_case();
  d["techniques"][0]["thresholds"] = json::parse(R"([{"metric": "stat_waves", "max": 1}])");
  msg = load_error(dir.write("direct.json", d.dump()));
  EXPECT_NE(msg.find("stat_waves"), std::string::npos) << msg;
  // A counter measures the run alone: no "against".
  d = valid_case();
  d["techniques"][0]["technique"] = "deferred";
  d["techniques"][0]["thresholds"] = json::parse(R"([{"metric": "stat_waves", "against": "golden", "max": 1}])");
  msg = load_error(dir.write("against.json", d.dump()));
  EXPECT_NE(msg.find("against"), std::string::npos) << msg;
}

// ---------------------------------------------------------------- tracking: variants, frames, curves

TEST(CaseTracking, VariantsEvalFramesConvergenceFlickerLoad) {
  TempDir dir;
  json d = valid_case();
  d["frames"] = 30;
  d["eval_frames"] = {10, 30};
  d["convergence"] = {{"roi", "centre"}, {"target", 2.0}, {"settle_frame", 5}};
  d["flicker_frames"] = 4;
  d["techniques"][0]["variants"] = {{"many-rays", {{"sky_rays", 16}}}};
  d["techniques"][0]["thresholds"] = {
      {{"metric", "uv_shift_max"}, {"against", "variant:many-rays"}, {"roi", "centre"}, {"max", 0.01}},
      {{"metric", "flip"}, {"roi", "centre"}, {"frame", 10}, {"max", 0.3}},
      {{"metric", "conv_error_max"}, {"max", 0.05}},
      {{"metric", "flicker"}, {"max", 0.1}},
      {{"metric", "scan_nan"}, {"max", 0}}};
  Case c = load_case(dir.write("tracking.json", d.dump()));
  EXPECT_EQ(c.eval_frames, (std::vector<uint32_t>{10, 30}));
  ASSERT_TRUE(c.convergence.has_value());
  EXPECT_EQ(c.convergence->roi, "centre");
  EXPECT_EQ(c.convergence->target, 2.0);
  EXPECT_EQ(c.convergence->settle_frame, 5u);
  EXPECT_EQ(c.flicker_frames, 4u);
  ASSERT_EQ(c.techniques[0].variants.count("many-rays"), 1u);
  EXPECT_EQ(c.techniques[0].variants.at("many-rays").at("sky_rays"), 16.0);
  EXPECT_EQ(c.techniques[0].thresholds[0].against, "variant:many-rays");
  EXPECT_EQ(c.techniques[0].thresholds[1].frame, 10u);
  EXPECT_EQ(c.techniques[0].thresholds[2].against, "");  // measured on the output alone
  // The convergence target defaults to the analytic value.
  d["convergence"].erase("target");
  d["analytic_value"] = 1.5;
  EXPECT_EQ(load_case(dir.write("target.json", d.dump())).convergence->target, 1.5);
}

TEST(CaseTracking, MalformedTrackingFieldsNameThePointer) {
  TempDir dir;
  json d = valid_case();
  d["frames"] = 30;
  auto with = [&](const std::function<void(json&)>& f) {
    json x = d;
    f(x);
    return x;
  };
  expect_error(dir, with([](json& x) { x["eval_frames"] = {10, 5}; }), "/eval_frames/1", "increasing");
  expect_error(dir, with([](json& x) { x["eval_frames"] = {31}; }), "/eval_frames/0", "integer in [1, 30]");
  expect_error(dir, with([](json& x) { x["convergence"] = {{"settle_frame", 2}}; }), "/convergence",
               "\"target\" (or a positive top-level analytic_value)");
  expect_error(dir, with([](json& x) { x["convergence"] = {{"roi", "nowhere"}, {"target", 1}}; }), "/convergence/roi",
               "(centre)");
  expect_error(dir, with([](json& x) { x["flicker_frames"] = 1; }), "/flicker_frames", "integer in [2, 30]");
  const std::string t0 = "/techniques/0/thresholds/0";
  expect_error(dir, with([](json& x) { x["techniques"][0]["thresholds"][0] = {{"metric", "flicker"}, {"max", 1}}; }),
               t0 + "/metric", "flicker_frames");
  expect_error(dir, with([](json& x) { x["techniques"][0]["thresholds"][0] = {{"metric", "conv_drift"}, {"max", 1}}; }),
               t0 + "/metric", "convergence");
  expect_error(dir,
               with([](json& x) {
                 x["techniques"][0]["thresholds"][0] = {{"metric", "flip"}, {"against", "variant:none"}, {"max", 1}};
               }),
               t0 + "/against", "reference, golden, analytic");
  expect_error(dir,
               with([](json& x) {
                 x["eval_frames"] = {10, 30};
                 x["techniques"][0]["thresholds"][0] = {{"metric", "flip"}, {"frame", 20}, {"max", 1}};
               }),
               t0 + "/frame", "one of the eval_frames (10, 30)");
  expect_error(dir, with([](json& x) { x["techniques"][0]["variants"] = {{"v", {{"sky_rayz", 1}}}}; }),
               "/techniques/0/variants/v/sky_rayz", "unknown option");
  expect_error(dir, with([](json& x) { x["techniques"][0]["variants"] = json::object(); }), "/techniques/0/variants",
               "non-empty object");
  // reference_spp 0: no reference, so nothing may be compared with it.
  expect_error(dir, with([](json& x) { x["reference_spp"] = 0; }), t0 + "/metric", "no reference");
}

TEST(CaseTracking, ConvergenceMetricsOnKnownCurves) {
  std::vector<double> flat(50, 2.0);
  for (const char* m : {"conv_error_final", "conv_error_max", "conv_drift", "conv_oscillation"})
    EXPECT_NEAR(convergence_metric(m, flat, 2.0, 1), 0.0, 1e-12) << m;
  std::vector<double> approach = {0.5, 0.9, 1.02, 0.98, 1.0};
  EXPECT_NEAR(convergence_metric("conv_error_final", approach, 1.0, 1), 0.0, 1e-12);
  EXPECT_NEAR(convergence_metric("conv_error_max", approach, 1.0, 3), 0.02, 1e-12);
  EXPECT_NEAR(convergence_metric("conv_error_max", approach, 1.0, 1), 0.5, 1e-12);
  // A ramp from 1.0 to 1.1 over 100 frames: the last 10 frames' mean minus the first 10's is
  // 0.1 - 0.1 * 9 / 99; a monotone curve does not oscillate.
  std::vector<double> ramp;
  for (int i = 0; i < 100; ++i) ramp.push_back(1.0 + 0.1 * i / 99.0);
  EXPECT_NEAR(convergence_metric("conv_drift", ramp, 1.0, 1), 0.1 - 0.1 * 9.0 / 99.0, 1e-12);
  EXPECT_NEAR(convergence_metric("conv_oscillation", ramp, 1.0, 1), 0.0, 1e-12);
  // Alternating 1.0 / 1.1: the 5-frame mean swings by 0.02 every frame.
  std::vector<double> ringing;
  for (int i = 0; i < 100; ++i) ringing.push_back(i % 2 ? 1.1 : 1.0);
  double osc = convergence_metric("conv_oscillation", ringing, 1.0, 10);
  EXPECT_GT(osc, 1.5);  // about 90 swings of 0.02
  EXPECT_LT(osc, 2.0);
  EXPECT_TRUE(std::isnan(convergence_metric("conv_error_max", {1.0, std::nan(""), 1.0}, 1.0, 1)));
  EXPECT_THROW(convergence_metric("conv_error_final", {}, 1.0, 1), CaseError);
}

}  // namespace
}  // namespace gib
