// `gibench run --attribute`: the error attribution (attribute_command.h attribute_row) of every
// technique row that ran whose case run says "attribute": true, in plan order on one device
// after the rows. Each such row's JSON gets "attribution": the summary attribute_row returns
// (its waterfall page, the largest stage per ROI) or {"error": ...}; without --attribute, a
// flagged row's JSON gets {"not_run": why}, so the report says the attribution was asked for and
// not made, never that there was nothing to attribute.
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "harness/case.h"
#include "harness/plan.h"
#include "harness/suite.h"
#include "harness/tier.h"

namespace gib {

// `cases`: the run's cases, already at `tier`; `rows`: the run's results (row JSON, report.h
// row_to_json), updated in place.
void attribute_flagged_rows(const SuiteOptions& o, Tier tier, const std::vector<Case>& cases,
                            const std::vector<PlannedRow>& ran, std::vector<nlohmann::json>& rows);

}  // namespace gib
