// Stage 4 of `gibench run`: a row's verdict. Every status a row can end with is decided here:
//   technique row:     pass | fail | known_failure (fails as the case records it for this device
//                      class and tier; a row marked so that passes fails, so a mark cannot go stale)
//   negative control:  pass (caught: a threshold failed) | fail (not caught) | skipped (what could
//                      catch it did not run, or the case records it is not caught here)
//   any row:           not_run (the profile left it out: plan.h)
//
//   plan (plan.h) -> render + evaluate (evaluate.h) -> verdict (this file) -> report (report.h)
#pragma once

#include <string>

#include "harness/case.h"
#include "harness/plan.h"
#include "harness/suite.h"

namespace gib {

// `failed`: what evaluate_row found (a check failed, the golden is missing, a non-finite output).
void technique_verdict(ResultRow& row, bool failed, const TechniqueRun& run, const std::string& device_class,
                       const std::string& tier);
void control_verdict(ResultRow& row, const NegativeControl& nc, const std::string& device_class,
                     const std::string& tier);
// A row the profile left out, with the reason.
ResultRow not_run_row(const Case& c, const PlannedRow& p, const TechniqueRun& run, const std::string& reason);

}  // namespace gib
