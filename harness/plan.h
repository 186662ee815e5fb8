// Stage 1 of `gibench run`: the plan. Every row of the selected cases in suite order, what each
// is expected to cost, and which of them this run renders: the profile (quick or full), the
// --technique filter and the shard decide; a row left out by the profile is reported as
// "not_run" with the reason, never as passed.
//
//   plan (this file) -> render + evaluate (evaluate.h) -> verdict (verdict.h) -> report (report.h)
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/case.h"

namespace gib {

// One row of the suite: "case/technique.preset" or "case/negative:name".
std::string row_key(const std::string& case_name, const std::string& kind, const std::string& technique,
                    const std::string& preset, const std::string& control);
// The key of a row as results.json records it (its case, kind, technique, preset, control).
std::string row_key_of(const nlohmann::json& row);

struct PlannedRow {
  std::string key;
  size_t case_index = 0;  // into the cases the plan was made from
  std::string kind;       // "technique" | "negative_control"
  size_t run_index = 0;   // Case::techniques (technique) or Case::negative_controls (control)
  std::string technique;  // TechniqueRun::technique (without the label)
  std::string preset;
  std::string control;    // the negative control's name
  double cost = 0;        // estimated_row_seconds
};

// Measured wall seconds per row key on lavapipe (one worker process per core of a 2-core
// machine), committed in cases/timings/lavapipe.json and written by `gibench run --profile full
// --record-timings`: the plan's costs where a row has one, the model's otherwise.
using RowSeconds = std::map<std::string, double>;
// {} when the file does not exist; a malformed file is an error naming it.
RowSeconds load_row_seconds(const std::string& cases_dir);
std::string row_seconds_path(const std::string& cases_dir);
// Replaces the recorded seconds of `rows` (atomically: a temporary file renamed); `how` says
// what measured them (device, workers).
void record_row_seconds(const std::string& cases_dir, const RowSeconds& rows, const std::string& how);

// Every row of `cases` in suite order: each case's technique rows (runs x presets), then its
// negative controls; each row's cost is its recorded seconds, else estimated_row_seconds.
std::vector<PlannedRow> plan_suite(const std::vector<Case>& cases, const RowSeconds& recorded = {});
std::vector<std::string> plan_rows(const std::vector<Case>& cases);  // their keys

// The run a planned row renders (a technique run, or the control's run).
const TechniqueRun& planned_run(const std::vector<Case>& cases, const PlannedRow& row);

// A model of a row's wall time on the default device (lavapipe, one worker process on one
// core), in seconds: frames rendered (the case's or the run's, its timing frames, once more per
// variant) x pixels x a per-technique cost per pixel-frame, plus a fixed overhead per render.
// Its constants were fitted to a full CI-tier run (plan.cpp); it orders rows (the parallel
// queue starts the longest first, the quick profile skips the slowest) and gives an ETA before
// any row time is recorded. Never a verdict.
double estimated_row_seconds(const Case& c, const TechniqueRun& run);

// quick: a subset that touches every case and every technique (see select_quick); full: every
// row. Default: quick at the CI tier on a CPU device (lavapipe), full elsewhere.
enum class Profile { quick, full };
Profile resolve_profile(const std::string& requested, bool cpu_device);
const char* profile_name(Profile p);

// The quick profile, deterministic for a given set of cases, in three parts:
//   1. each case's cheapest technique row (every case is touched) and its cheapest negative
//      control unless that control is a slow row;
//   2. each technique's cheapest row, where part 1 has none of it;
//   3. every kQuickStride-th row of the plan (interleaved, as Mesa runs a fraction of a
//      conformance suite) among the rows under kQuickSlowRowSeconds.
// Returns, per row key left out, the reason; rows not in the map are run.
inline constexpr size_t kQuickStride = 4;
inline constexpr double kQuickSlowRowSeconds = 20.0;
std::map<std::string, std::string> select_quick(const std::vector<Case>& cases, const std::vector<PlannedRow>& plan);

}  // namespace gib
