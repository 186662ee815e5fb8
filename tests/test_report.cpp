// The HTML report of `gibench run`: a synthetic SuiteResult (two cases, passing and failing
// rows, a negative control, a case error) written with write_suite_outputs, then loaded in
// headless Chromium. The page sets body[data-gib-status] to "ok" once everything rendered and
// every image loaded, or "error: <what>" on a failed image or a script error; the checker
// (harness/report_check.h, also `gibench check-report` in ci/suite.sh) reads it from --dump-dom
// and Chromium's log for console output from the page.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "harness/report.h"
#include "harness/report_check.h"
#include "harness/suite.h"

namespace gib {
namespace {

namespace fs = std::filesystem;

const char* kFailMessage = "flip vs reference 0.2134 > max 0.15 (by 0.0634)";
const char* kCaughtMessage = "caught as expected: flip vs reference 0.4101 > max 0.15 (by 0.2601)";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Text as Chromium serialises it inside an element (--dump-dom).
std::string html_text(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '&') o += "&amp;";
    else if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else o += c;
  }
  return o;
}

fs::path make_temp_dir(const std::string& tag) {
  std::string templ = (fs::temp_directory_path() / ("gib_report_" + tag + "_XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  if (!mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed for " + templ);
  return fs::path(buf.data());
}

#define REQUIRE_CHROMIUM(var)                                                                              \
  const std::string var = find_chromium();                                                                 \
  ASSERT_FALSE(var.empty()) << "chromium is not installed (not on PATH): the report test needs headless Chromium; " \
                               "run ci/setup.sh (it installs the apt package `chromium`)"

// A small image with a gradient and a bright patch (values above 1, for the exposure control).
FloatImage synthetic_image(uint32_t w, uint32_t h, float tint, float noise) {
  FloatImage img(w, h, 4, 1.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      float u = (x + 0.5f) / w, v = (y + 0.5f) / h;
      float wobble = noise * std::sin(float(x * 7 + y * 13));
      float lum = 0.05f + 0.6f * u * (1.0f - v) + wobble;
      bool patch = u > 0.6f && u < 0.8f && v > 0.2f && v < 0.45f;
      img.at(x, y, 0) = patch ? 6.0f : lum * (1.0f + tint);
      img.at(x, y, 1) = patch ? 5.0f : lum * 0.8f;
      img.at(x, y, 2) = patch ? 3.0f : lum * (1.0f - tint) + 0.1f * v;
    }
  return img;
}

FloatImage synthetic_error(uint32_t w, uint32_t h, float amount) {
  FloatImage e(w, h, 1);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      e.at(x, y, 0) = std::fmin(1.0f, amount * (0.3f + 0.7f * std::fabs(std::sin(x * 0.21f) * std::cos(y * 0.17f))));
  return e;
}

PlannedPass planned(const std::string& name, bool runs, const std::string& reason = "") {
  PlannedPass p;
  p.name = name;
  p.runs = runs;
  p.reason = reason;
  return p;
}

CheckResult check(const std::string& metric, const std::string& against, const std::string& roi, double value,
                  std::optional<double> max, std::optional<double> min, bool pass, const std::string& message) {
  CheckResult c;
  c.metric = metric;
  c.against = against;
  c.roi = roi;
  c.value = value;
  c.max = max;
  c.min = min;
  c.pass = pass;
  c.message = message;
  return c;
}

struct Fixture {
  SuiteResult suite;
  std::vector<Case> cases;
};

ResultRow row(const std::string& case_name, const std::string& technique, const std::string& preset,
              const std::string& status, double flip, double psnr, double gpu_ms) {
  ResultRow r;
  r.case_name = case_name;
  r.technique = technique;
  r.preset = preset;
  r.kind = "technique";
  r.status = status;
  r.metrics = {{"flip_vs_reference", flip}, {"psnr_vs_reference", psnr}, {"flip_vs_golden", flip * 0.02},
               {"relmse_vs_reference", flip * flip}, {"nan_count", 0}, {"inf_count", 0}};
  r.gpu_ms = gpu_ms;
  r.device = "Synthetic GPU";
  r.image_id = case_name + "__" + technique + "." + preset;
  r.reference_id = case_name + "__reference.radiance";
  r.plan.passes = {planned("gbuffer", true), planned(technique, true), planned("tonemap", true),
                   planned("taa", false, "output 'history' is not requested")};
  r.passes = {{"gbuffer", 0.21 * gpu_ms, 0.19 * gpu_ms, 0.25 * gpu_ms},
              {technique, 0.66 * gpu_ms, 0.6 * gpu_ms, 0.72 * gpu_ms},
              {"tonemap", 0.13 * gpu_ms, 0.12 * gpu_ms, 0.15 * gpu_ms}};
  r.checks.push_back(check("flip", "golden", "", flip * 0.02, 0.01, std::nullopt, flip * 0.02 <= 0.01,
                           "flip vs golden ok"));
  return r;
}

// Two cases: "cornell_box" (two techniques, one failing, and a negative control) and
// "sun_sky" (one technique), plus a case error. Images go to dir/img.
Fixture write_fixture(const fs::path& dir, bool float_data = true) {
  const uint32_t w = 64, h = 36;
  Fixture f;
  Case a;
  a.name = "cornell_box";
  a.description = "Closed box, one area light: indirect bounce colour bleeding from the red and green walls.";
  a.width = w;
  a.height = h;
  a.rois = {Roi{"left_wall", 0.0f, 0.1f, 0.3f, 0.9f}, Roi{"light", 0.6f, 0.2f, 0.8f, 0.45f}};
  Case b;
  b.name = "sun_sky";
  b.description = "Open scene lit by the sun and sky only.";
  b.width = w;
  b.height = h;
  f.cases = {a, b};

  f.suite.device.name = "Synthetic GPU";
  f.suite.device.type = "discrete";
  f.suite.device.driver_name = "TestDriver";
  f.suite.device.driver_info = "1.2.3";
  f.suite.device_class = "synthetic";

  ResultRow good = row("cornell_box", "ddgi", "medium", "pass", 0.081, 27.5, 1.9);
  good.options = {{"max_bounces", 2}};
  good.checks.push_back(check("flip", "reference", "", 0.081, 0.15, std::nullopt, true, "flip vs reference 0.081 ok"));
  good.checks.push_back(
      check("roi_ratio", "reference", "left_wall", 0.97, 1.1, 0.9, true, "roi_ratio vs reference [left_wall] 0.97 ok"));
  ResultRow bad = row("cornell_box", "ssgi", "low", "fail", 0.2134, 19.2, 0.8);
  bad.checks.push_back(check("flip", "reference", "", 0.2134, 0.15, std::nullopt, false, kFailMessage));
  bad.messages.push_back(kFailMessage);
  ResultRow neg = row("cornell_box", "ddgi", "medium", "pass", 0.4101, 12.1, 1.7);
  neg.kind = "negative_control";
  neg.control_name = "no_indirect";
  neg.control_why = "max_bounces = 0 removes all indirect light";
  neg.options = {{"max_bounces", 0}};
  neg.image_id += ".negative";
  neg.checks = {check("flip", "reference", "", 0.4101, 0.15, std::nullopt, false,
                      "flip vs reference 0.4101 > max 0.15 (by 0.2601)")};
  neg.messages = {kCaughtMessage};
  ResultRow sky = row("sun_sky", "direct", "high", "pass", 0.05, 31.0, 0.6);
  sky.plan.passes.push_back(planned("sky_lut", false, "sky is constant: baked at load"));
  f.suite.rows = {good, bad, neg, sky};
  f.suite.case_errors = {"sun_sky: golden.json: unreadable noise floor record"};

  fs::path img = dir / "img";
  fs::create_directories(img);
  write_report_image((img / "cornell_box__reference.radiance").string(), synthetic_image(w, h, 0.2f, 0.0f));
  write_report_image((img / "sun_sky__reference.radiance").string(), synthetic_image(w, h, -0.3f, 0.0f));
  float amount = 0.1f;
  for (auto& r : f.suite.rows) {
    write_report_image((img / r.image_id).string(), synthetic_image(w, h, r.case_name == "sun_sky" ? -0.3f : 0.2f,
                                                                    float(r.metrics["flip_vs_reference"]) * 0.3f));
    write_report_error_map((img / (r.image_id + ".flip")).string(), synthetic_error(w, h, amount));
    amount += 0.25f;
  }
  if (!float_data)
    for (auto& r : f.suite.rows) fs::remove(img / (r.image_id + ".js"));
  write_suite_outputs(dir.string(), f.suite, f.cases);
  return f;
}

void expect_clean_console(const BrowserRun& r) {
  for (auto& line : r.page_console) ADD_FAILURE() << "console output from the report page: " << line;
}

TEST(Report, RendersInHeadlessChromium) {
  REQUIRE_CHROMIUM(chromium);
  fs::path dir = make_temp_dir("ok");
  Fixture f = write_fixture(dir);
  ASSERT_TRUE(fs::exists(dir / "index.html"));
  ASSERT_TRUE(fs::exists(dir / "results.js"));
  std::string html = read_file(dir / "index.html");
  EXPECT_EQ(html.find("<!--GIB_IMAGE_SCRIPTS-->"), std::string::npos);
  EXPECT_NE(html.find("<script src=\"img/cornell_box__reference.radiance.js\">"), std::string::npos);

  BrowserRun r = run_chromium(chromium, dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_EQ(r.status, "ok") << r.describe();
  expect_clean_console(r);
  for (auto& c : f.cases) EXPECT_NE(r.out.find(c.name), std::string::npos) << c.name;
  for (auto& c : f.cases) EXPECT_NE(r.out.find(html_text(c.description)), std::string::npos) << c.description;
  EXPECT_NE(r.out.find(html_text(kFailMessage)), std::string::npos) << "failing message missing from the DOM";
  EXPECT_NE(r.out.find(html_text(kCaughtMessage)), std::string::npos);
  EXPECT_NE(r.out.find("no_indirect"), std::string::npos);
  EXPECT_NE(r.out.find(html_text("max_bounces = 0 removes all indirect light")), std::string::npos);
  EXPECT_NE(r.out.find("unreadable noise floor record"), std::string::npos) << "case error missing";
  EXPECT_NE(r.out.find("culled"), std::string::npos);
  EXPECT_NE(r.out.find(html_text("sky is constant: baked at load")), std::string::npos) << "cull reason missing";
  EXPECT_NE(r.out.find("Synthetic GPU"), std::string::npos);
  EXPECT_NE(r.out.find("<canvas"), std::string::npos) << "float images not drawn into canvases";
  EXPECT_NE(r.out.find("cornell_box__ssgi.low.flip.png"), std::string::npos);

  fs::path shot = dir / "shot.png";
  BrowserRun s = run_chromium(chromium, dir.string(), shot.string());
  EXPECT_EQ(s.exit_code, 0) << s.describe();
  expect_clean_console(s);
  ASSERT_TRUE(fs::exists(shot)) << s.describe();
  EXPECT_GT(fs::file_size(shot), 10000u);
  std::printf("report screenshot: %s\n", shot.string().c_str());
}

TEST(Report, FallsBackToPngWithoutFloatData) {
  REQUIRE_CHROMIUM(chromium);
  fs::path dir = make_temp_dir("png");
  write_fixture(dir, /*float_data=*/false);
  BrowserRun r = run_chromium(chromium, dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_EQ(r.status, "ok") << r.describe();
  expect_clean_console(r);
  EXPECT_NE(r.out.find("src=\"img/cornell_box__ssgi.low.png\""), std::string::npos) << "no PNG fallback";
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST(Report, MissingImageIsAnError) {
  REQUIRE_CHROMIUM(chromium);
  fs::path dir = make_temp_dir("missing");
  write_fixture(dir);
  ASSERT_TRUE(fs::remove(dir / "img" / "cornell_box__ssgi.low.flip.png"));
  BrowserRun r = run_chromium(chromium, dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_EQ(r.status.rfind("error:", 0), 0u) << "status '" << r.status << "'";
  EXPECT_NE(r.status.find("cornell_box__ssgi.low.flip.png"), std::string::npos) << r.status;
  EXPECT_FALSE(r.page_console.empty()) << "the page should log the failure with console.error";
  EXPECT_NE(r.problem().find("error banner"), std::string::npos) << r.problem();  // gibench check-report's line
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST(Report, MissingResultsIsAnError) {
  REQUIRE_CHROMIUM(chromium);
  fs::path dir = make_temp_dir("noresults");
  write_fixture(dir);
  ASSERT_TRUE(fs::remove(dir / "results.js"));
  BrowserRun r = run_chromium(chromium, dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_EQ(r.status.rfind("error:", 0), 0u) << "status '" << r.status << "'";
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace gib

namespace gib {
namespace {

// A real run (not a fixture) of `cases`' radiance-cache rows with the stability scan off, its
// report loaded in headless Chromium: clean, every row timed on scan-free frames. Returns
// results.json's text.
std::string real_run_report(const std::string& chromium, const std::vector<std::string>& cases, const std::string& tag) {
  SuiteOptions o;
  o.case_globs = cases;
  o.techniques = {"radiance-cache"};  // the rows and controls in question; the other rows only cost time
  o.cases_dir = std::string(GIB_SOURCE_DIR) + "/cases";
  o.goldens_dir = std::string(GIB_SOURCE_DIR) + "/goldens";
  fs::path dir = make_temp_dir(tag);
  o.out = dir.string();
  o.stability_scan = false;
  EXPECT_EQ(cmd_run(o), 0);
  std::string results = read_file(dir / "results.json");
  // Every row's times come from scan-free timing frames (perf/frame_timing.h).
  EXPECT_NE(results.find("\"scan_free\": true"), std::string::npos);
  EXPECT_EQ(results.find("\"scan_free\": false"), std::string::npos);
  BrowserRun r = run_chromium(chromium, dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_EQ(r.status, "ok") << r.describe();
  expect_clean_console(r);
  EXPECT_EQ(r.problem(), "");
  std::error_code ec;
  fs::remove_all(dir, ec);
  return results;
}

// The variant-only case has no reference image: the page once showed "failed to load
// img/...__reference.indirect_diffuse.png" after a clean run.
TEST(Report, RealRunOfAVariantOnlyCaseLoadsCleanly) {
  REQUIRE_CHROMIUM(chromium);
  std::string results = real_run_report(chromium, {"r11g11b10-vs-rgb9e5"}, "real");
  EXPECT_EQ(results.find("r11g11b10-vs-rgb9e5__reference"), std::string::npos) << "a reference image it does not have";
}

// extreme-range-exterior, whose negative control only a scan_* threshold catches: with the scan
// off that control is "skipped", the technique rows still pass, the run passes. Three 256-frame
// radiance-cache rows: 200 s on two cores, so in the slow set.
TEST(SlowReport, RealRunWithoutTheScanSkipsScanThresholds) {
  REQUIRE_CHROMIUM(chromium);
  std::string results = real_run_report(chromium, {"extreme-range-exterior"}, "real_scan");
  EXPECT_NE(results.find("\"status\": \"skipped\""), std::string::npos) << "the scan-only control is not skipped";
  EXPECT_NE(results.find("scan_saturated skipped: the stability scan did not run"), std::string::npos);
}

}  // namespace
}  // namespace gib
