// Stage 2 of `gibench run`: render one planned row and evaluate it. The row's output is compared
// with its case's reference, analytic value, approved golden and variants; every threshold
// becomes a check (measure.h); the images the report shows are written. Whether the row passes
// is decided by verdict.h from what this stage found.
//
//   plan (plan.h) -> render + evaluate (this file) -> verdict (verdict.h) -> report (report.h)
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>

#include "harness/goldens.h"
#include "harness/suite.h"

namespace gib {

class Gpu;

// What every row of one case reads: its goldens, its references (loaded once, by AOV and frame),
// the device class and tier its known failures and goldens are keyed by.
struct CaseContext {
  const Case& c;
  GoldenStore store;       // approved technique goldens of the tier
  GoldenStore refs;        // the references of the tier (committed, or the GPU tier's cache entry)
  std::string tier;
  std::string cls;         // the device's class: known failures
  std::string golden_cls;  // whose approved technique goldens rows are compared with
  std::map<std::string, FloatImage> references;  // by AOV
  std::optional<FloatImage> analytic;
  const SuiteOptions& o;
};

// Frames of the row's renders as they finish: (what: "" for the row's own render, else
// "variant NAME"), done, total.
using RowProgress = std::function<void(const std::string& what, uint32_t done, uint32_t total)>;

struct Evaluation {
  ResultRow row;       // metrics, checks, messages, images; status not yet decided
  bool failed = false; // a check failed, the golden is missing or the output is not finite
};
Evaluation evaluate_row(CaseContext& ctx, Gpu& gpu, const TechniqueRun& run, const std::string& preset,
                        const std::string& kind, const std::string& control_name, const RowProgress& progress = {});

// The FLIP between two reference renders with different seeds (goldens.h, measure_noise_floor).
// --noise-floor measures it at the spp golden.json records for the committed reference and
// records it in golden.json (metadata only; no golden image is touched); every run rejects flip
// bounds vs the reference below 3x the recorded floor (check_noise_floor_bounds).
void check_noise_floor(CaseContext& ctx, Gpu& gpu);

// Report previews of the references the case's rows were compared with (per-frame cases: the
// last frame's), under DIR/img/<case>__reference.<aov>.
void write_reference_previews(const CaseContext& ctx);

}  // namespace gib
