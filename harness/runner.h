// `gibench run`: every case x technique x preset against the reference and the approved
// goldens, expectations and negative controls; writes results.json, junit.xml and the HTML
// report; exit code non-zero when anything fails.
// `gibench update-goldens`: renders and replaces goldens on request, atomically, with history.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "harness/case.h"
#include "renderer/image/float_image.h"
#include "harness/render.h"
#include "perf/frame_timing.h"
#include "renderer/graph/stability.h"
#include <nlohmann/json.hpp>
#include <optional>

namespace gib {

struct SuiteOptions {
  std::vector<std::string> case_globs;  // empty: all
  std::string cases_dir = "cases";
  std::string goldens_dir = "goldens";
  std::string out = "out";
  std::string device;
  bool validate = false;
  bool noise_floor = false;  // run: also render each reference twice and record the floor
  bool stability_scan = true;  // run: GPU scan of every written resource (renderer/graph/stability.h)
  // run: the device class whose approved technique goldens rows are compared with; empty: the
  // device's own (harness/goldens.h device_class). Known failures always follow the device.
  std::string golden_class;
  // run: "K/N" runs the rows i with i % N == K of the suite's plan (harness/shard.h); empty:
  // every row. (The CLI fills it from GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS when --shard is
  // not given; the library never reads them, so a sharded test binary does not shard suites.)
  std::string shard;
  // run: only rows (and negative controls) of these techniques; empty: every technique. Cases
  // with none are skipped whole.
  std::vector<std::string> techniques;
  // "ci" | "gpu" | "" (by device: ci on lavapipe, gpu elsewhere; harness/tier.h).
  std::string tier;
  // The GPU tier's reference cache (harness/tier.h reference_cache_root; "" = the default).
  std::string reference_cache;
};

struct CheckResult {
  std::string metric, against, roi;
  double value = 0;
  std::optional<double> max, min;
  bool pass = true;
  // Not evaluated: the metric needs what this run did not produce (scan_* under
  // --no-stability-scan). Neither passes nor fails the row; listed in its messages.
  bool skipped = false;
  std::string message;  // "flip vs reference 0.21 > max 0.15 (by 0.06)"
};

struct ResultRow {
  std::string case_name, technique, preset, kind;  // kind: "technique" | "negative_control"
  std::string control_name, control_why;
  std::map<std::string, double> options;
  // pass | fail | error | known_failure (TechniqueRun::known_failure, failing as known) | skipped (a
  // negative control whose every threshold was skipped: nothing could catch it)
  std::string status;
  std::vector<std::string> messages;
  // The device class of the approved golden this row was compared with ("" when none). Differs
  // from the suite's class when this device has no golden of its own and the plain (lavapipe)
  // file stood in: said in the row's messages and shown amber in the report.
  std::string golden_class;
  std::map<std::string, double> metrics;
  std::vector<CheckResult> checks;
  double gpu_ms = 0;  // median per frame, over timing.frames
  perf::FrameTiming timing;  // the frames GPU times come from (scan-free, after all reads)
  std::vector<double> curve;  // Case::convergence: ROI mean per frame
  double curve_target = 0;
  std::vector<uint32_t> eval_frames;  // frames the thresholds were evaluated at
  bool scanned = false;               // the stability scan ran (SuiteOptions::stability_scan)
  StabilityReport stability;
  std::vector<PassStats> passes;
  Plan plan;
  uint64_t texture_bytes = 0;  // the scene's packed image textures on the GPU
  std::string image_id;      // files under DIR/img/: <id>.png, <id>.js, <id>.flip.png, <id>.exr
  std::string reference_id;  // the reference AOV it was compared with: DIR/img/<id>.png/.js
  std::vector<std::pair<std::string, std::string>> views;  // technique debug views: name, image id
  std::map<std::string, std::string> printouts;            // technique debug printouts: name, text
  std::string device;
};

// Clock-probe ratio (around the timed frames / its fastest, perf/clock_probe.h) above which a
// row says its GPU times were taken at a lowered clock.
inline constexpr double kClockDropWarn = 1.10;

struct SuiteResult {
  DeviceInfo device;
  std::string device_class;
  std::string golden_class;  // SuiteOptions::golden_class, or device_class
  std::string tier;          // "ci" or "gpu" (harness/tier.h)
  // Per case at the GPU tier: {"key", "dir", "spp", "noise_floor", "rendered": this run made it}.
  nlohmann::json references = nlohmann::json::object();
  // A sharded run: {"index", "count", "plan" (every row key of the suite, in order), "rows"
  // (this shard's)}; null otherwise.
  nlohmann::json shard;
  std::vector<ResultRow> rows;
  std::vector<std::string> case_errors;  // "<case>: message"
  int failures() const;
};

int cmd_run(const SuiteOptions& o);

struct UpdateOptions {
  SuiteOptions suite;
  std::vector<std::string> techniques;  // empty: all of the case's
  bool reference = false;               // (re)render the path-traced reference
  uint32_t spp = 0;                     // with reference: spp of this render (0: the case's reference_spp)
  bool noise_floor = false;             // with reference: also render seed + 1000, record the floor
  bool only_reference = false;          // with reference: no technique golden is rendered
  std::string reason;
  bool yes = true;                      // no interactive confirmation (CI, scripts)
  // Approve the technique outputs of a finished `gibench run` (its --out folder: results.json and
  // img/<row>.exr) instead of rendering them again: the device class and tier are the run's.
  std::string from_run;
};
int cmd_update_goldens(const UpdateOptions& o);

bool glob_match(const std::string& pattern, const std::string& text);
std::vector<Case> select_cases(const SuiteOptions& o);
// Whether rows of `technique` are in a --technique list (empty: every technique).
bool technique_selected(const std::vector<std::string>& techniques, const std::string& technique);

// What the per-run metrics read beyond one image: the convergence curve (ROI mean luminance
// per frame, conv_*) and the last frames (flicker).
struct MetricSeries {
  const std::vector<double>* curve = nullptr;
  const std::vector<FloatImage>* frames = nullptr;
  const StabilityReport* stability = nullptr;  // scan_* metrics
  const std::vector<double>* nan_pixels = nullptr;  // nan_frames / nan_last_frame / nan_max_pixels
};

// The metric named by a threshold, of `output` against `against` (may be empty for metrics
// that need none), inside roi (normalised; whole image when absent).
double compute_metric(const Case& c, const std::string& metric, const FloatImage& output, const FloatImage* against,
                      const Roi* roi, const MetricSeries& series = {});

// The convergence metrics of a curve m (one value per frame) towards target t, from the 1-based
// settle_frame on; see case.h for their definitions.
double convergence_metric(const std::string& metric, const std::vector<double>& m, double target,
                          uint32_t settle_frame);

}  // namespace gib
