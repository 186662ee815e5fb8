#include "harness/verdict.h"

#include <fmt/format.h>

#include <algorithm>

namespace gib {

void technique_verdict(ResultRow& row, bool failed, const TechniqueRun& run, const std::string& device_class,
                       const std::string& tier) {
  row.status = failed ? "fail" : "pass";
  const std::string known = run.known_failure_on(device_class, tier);
  if (known.empty()) return;
  if (failed) {
    row.status = "known_failure";
    row.messages.insert(row.messages.begin(), "known failure: " + known);
  } else {
    row.status = "fail";
    row.messages.push_back(fmt::format(
        "marked known_failure on {} at the {} tier but every check passed: remove it from the case ({})", device_class,
        tier, known));
  }
}

void control_verdict(ResultRow& row, const NegativeControl& nc, const std::string& device_class,
                     const std::string& tier) {
  row.control_name = nc.name;
  row.control_why = nc.why;
  const bool caught = std::any_of(row.checks.begin(), row.checks.end(), [](auto& cr) { return !cr.pass; });
  std::vector<std::string> skipped;
  for (auto& cr : row.checks)
    if (cr.skipped) skipped.push_back(cr.message);
  row.messages.clear();
  const std::string not_caught = nc.not_caught_reason(device_class, tier);
  if (!not_caught.empty()) {  // measured not to show here: an uncaught control is expected
    row.status = caught ? "fail" : "skipped";
    row.messages.push_back(caught ? fmt::format("negative control '{}' is marked not_caught_on {} at the {} tier "
                                                "but was caught: remove the mark ({})",
                                                nc.name, device_class, tier, not_caught)
                                  : fmt::format("not caught on {} at the {} tier, as the case records: {}",
                                                device_class, tier, not_caught));
  } else if (!caught && !skipped.empty()) {  // what could have caught it did not run
    row.status = "skipped";
    row.messages = skipped;
  } else if (caught) {
    row.status = "pass";
    for (auto& cr : row.checks)
      if (!cr.pass) row.messages.push_back("caught as expected: " + cr.message);
  } else {
    row.status = "fail";
    row.messages.push_back(fmt::format(
        "negative control '{}' passed every threshold: the case cannot tell good from bad ({})", nc.name, nc.why));
  }
}

ResultRow not_run_row(const Case& c, const PlannedRow& p, const TechniqueRun& run, const std::string& reason) {
  ResultRow row;
  row.case_name = c.name;
  row.technique = run.name();
  row.preset = p.preset;
  row.kind = p.kind;
  row.control_name = p.control;
  row.options = run.options;
  row.status = "not_run";
  row.messages.push_back(reason);
  if (p.kind == "negative_control")
    for (auto& nc : c.negative_controls)
      if (nc.name == p.control) row.control_why = nc.why;
  return row;
}

}  // namespace gib
