// The scenario suite's options, rows and results, shared by its stages:
//   plan (plan.h) -> render + evaluate (evaluate.h, measure.h) -> verdict (verdict.h)
//   -> report (report.h), run in one process or in worker processes (jobs.h) by cmd_run (run.cpp).
// `gibench update-goldens` (update_goldens.cpp) renders and replaces goldens on request,
// atomically, with history.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "harness/case.h"
#include "harness/measure.h"
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
  // The GPU tier's reference cache (harness/references.h reference_cache_root; "" = the default).
  std::string reference_cache;
  // run: "quick" | "full" | "" (by device: quick on a CPU device at the CI tier, full elsewhere;
  // plan.h). The library's default is full; the CLI's is "".
  std::string profile = "full";
  // run: rows rendered at once, each worker a process of its own (jobs.h); 0: by device (one
  // per core on a CPU device, kGpuJobs per GPU otherwise).
  unsigned jobs = 1;
  // run: frames recorded into one GPU submission between the host's reads of a row's output
  // (Executor::run_frames; 1 = a submit-and-wait per frame). Output is the same at any value.
  unsigned frames_per_submission = 64;
  // run: write each finished row's wall seconds into cases/timings/lavapipe.json (plan.h
  // RowSeconds; rows of other cases keep theirs). Only on a CPU device.
  bool record_timings = false;
  // run: print the plan (each row, run or not and why, its expected seconds) and render nothing.
  bool dry_run = false;
  // run: after the rows, the error attribution of every row that ran whose case run says
  // "attribute": true (harness/attribution/suite_attribution.h), linked from the report.
  bool attribute = false;
  // run: a worker of a parallel run (jobs.h): row keys arrive on stdin, events leave on stdout.
  bool worker = false;
  // run: the gibench binary the workers run ("": this process's own, /proc/self/exe; a test
  // binary names the gibench it was built beside).
  std::string worker_exe;
};

struct ResultRow {
  std::string case_name, technique, preset, kind;  // kind: "technique" | "negative_control"
  std::string control_name, control_why;
  std::map<std::string, double> options;
  // pass | fail | error | known_failure (TechniqueRun::known_failure, failing as known) | skipped (a
  // negative control whose every threshold was skipped: nothing could catch it) | not_run (the
  // profile left it out; its message says why and which profile runs it)
  std::string status;
  std::vector<std::string> messages;
  // The device class of the approved golden this row was compared with ("" when none). Differs
  // from the suite's class when this device has no golden of its own and the plain (lavapipe)
  // file stood in: said in the row's messages and shown amber in the report.
  std::string golden_class;
  std::map<std::string, double> metrics;
  std::vector<CheckResult> checks;
  double gpu_ms = 0;  // median per frame, over timing.frames
  double wall_s = 0;  // wall-clock seconds the row took: render, evaluation, images
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

}  // namespace gib
