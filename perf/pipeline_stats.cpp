#include "perf/pipeline_stats.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace gib::perf {

void add_pipelines(std::vector<const Pipeline*>& pipelines, const std::vector<const Pipeline*>& ran) {
  for (const Pipeline* p : ran)
    if (p && std::find(pipelines.begin(), pipelines.end(), p) == pipelines.end()) pipelines.push_back(p);
}

namespace {
// Integers as integers; an integer of 2^32 or more in hex, as the driver set its bits (NVIDIA's
// "Local Memory Size" reads 0x1000000160: bit 36 set above what reads as 352 bytes).
std::string value_text(double v) {
  if (v != std::floor(v) || std::fabs(v) >= 1.8e19) return fmt::format("{:.4g}", v);
  if (v >= 4294967296.0) return fmt::format("{:#x}", uint64_t(v));
  return fmt::format("{:.0f}", v);
}
}  // namespace

std::string pipeline_statistics_line(const std::vector<const Pipeline*>& pipelines) {
  std::string out;
  for (const Pipeline* p : pipelines) {
    const auto& stats = p->statistics();
    if (stats.empty()) continue;
    std::set<std::string> executables;
    for (const PipelineStatistic& s : stats) executables.insert(s.executable);
    std::string parts;
    for (const PipelineStatistic& s : stats) {
      const std::string who = executables.size() > 1 ? s.executable + " " : "";
      parts += fmt::format("{}{}{} {}", parts.empty() ? "" : ", ", who, s.name, value_text(s.value));
    }
    out += fmt::format("{}{}: {}", out.empty() ? "" : "; ", p->name(), parts);
  }
  return out;
}

nlohmann::json pipeline_statistics_json(const std::vector<const Pipeline*>& pipelines) {
  nlohmann::json out = nlohmann::json::array();
  for (const Pipeline* p : pipelines) {
    nlohmann::json stats = nlohmann::json::array();
    for (const PipelineStatistic& s : p->statistics())
      stats.push_back({{"executable", s.executable}, {"name", s.name}, {"value", s.value}});
    out.push_back({{"name", p->name()}, {"statistics", stats}});
  }
  return out;
}

}  // namespace gib::perf
