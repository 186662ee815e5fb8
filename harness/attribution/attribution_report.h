// Error attribution's outputs: the console table, the JSON record and a self-contained HTML page
// with one waterfall per ROI (the technique's error stepping down by each stage's Shapley bar,
// bias^2 solid and variance light, to the oracle floor; the reference's noise floor x3 dashed).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/attribution/attribution.h"

namespace gib::attribution {

struct StageInfo {
  std::string name;
  std::vector<std::string> passes;
  std::string oracle;  // empty: none yet (not in the game)
};

struct ReportContext {
  std::string case_name, row, preset, aov, device;
  std::vector<StageInfo> stages;  // every stage of the technique, in pass order
};

// "probes, upscale" for the stages of `mask`; "none" for 0.
std::string mask_names(const std::vector<std::string>& stages, uint32_t mask);
std::string format_table(const Attribution& a, const ReportContext& ctx);
nlohmann::json to_json(const Attribution& a, const ReportContext& ctx);
std::string waterfall_html(const Attribution& a, const ReportContext& ctx);
// The pieces of the page: one waterfall per ROI, and the page around a body.
std::string waterfalls(const Attribution& a);
std::string html_page(const Attribution& a, const ReportContext& ctx, const std::string& body);

// Lag attribution (attribution.h LagAttribution): the integrated game's table, then a table per
// ROI of each frame's error, bars and largest share; the JSON of the integrated game with "lag":
// {"frames", "integration", "per_frame": [{"frame", "rois"}]}; the page with the integrated
// waterfall per ROI and the per-frame tables. In lag_report.cpp.
std::string format_table(const LagAttribution& a, const ReportContext& ctx);
nlohmann::json to_json(const LagAttribution& a, const ReportContext& ctx);
std::string waterfall_html(const LagAttribution& a, const ReportContext& ctx);

}  // namespace gib::attribution
