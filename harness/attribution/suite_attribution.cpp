#include "harness/attribution/suite_attribution.h"

#include <fmt/format.h>

#include <chrono>
#include <map>

#include "harness/attribution/attribute_command.h"

namespace gib {

void attribute_flagged_rows(const SuiteOptions& o, Tier tier, const std::vector<Case>& cases,
                            const std::vector<PlannedRow>& ran, std::vector<nlohmann::json>& rows) {
  std::map<std::string, nlohmann::json*> by_key;
  for (nlohmann::json& r : rows) by_key[row_key_of(r)] = &r;
  std::vector<const PlannedRow*> flagged;
  for (const PlannedRow& p : ran)
    if (p.kind == "technique" && planned_run(cases, p).attribute && by_key.count(p.key)) flagged.push_back(&p);
  if (flagged.empty()) return;
  if (!o.attribute) {
    for (const PlannedRow* p : flagged)
      (*by_key[p->key])["attribution"] = {{"not_run", "asked for by the case; runs with gibench run --attribute"}};
    return;
  }
  auto gpu = Gpu::create({o.device, o.validate});
  fmt::print("attribution of {} flagged row{} on {}\n", flagged.size(), flagged.size() == 1 ? "" : "s",
             gpu->info().name);
  for (size_t i = 0; i < flagged.size(); ++i) {
    const PlannedRow& p = *flagged[i];
    const Case& c = cases[p.case_index];
    nlohmann::json& row = *by_key[p.key];
    const auto t0 = std::chrono::steady_clock::now();
    try {
      row["attribution"] = attribute_row(*gpu, c, tier, planned_run(cases, p), p.preset, {}, o, false);
      std::string largest;
      for (const auto& r : row["attribution"]["rois"])
        largest += fmt::format("{}{}: {}", largest.empty() ? "" : ", ", r["roi"].get<std::string>(),
                               r["largest"].get<std::string>());
      fmt::print("  [{}/{}] {} ({:.0f} s): largest share {}\n", i + 1, flagged.size(), p.key,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), largest);
    } catch (const std::exception& e) {
      row["attribution"] = {{"error", e.what()}};
      fmt::print("  [{}/{}] {}: attribution error: {}\n", i + 1, flagged.size(), p.key, e.what());
    }
  }
}

}  // namespace gib
