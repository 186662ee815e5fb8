#include "harness/attribution/attribution_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace gib::attribution {

namespace {

const StageBar* bar_of(const RoiAttribution& r, const std::string& stage) {
  for (const StageBar& b : r.stages)
    if (b.stage == stage) return &b;
  return nullptr;
}

std::string share(double part, double gap) { return gap > 0 ? fmt::format("{:.1f}%", 100.0 * part / gap) : "-"; }

nlohmann::json error_json(const RoiError& e) {
  return {{"mse", e.mse},
          {"bias2", e.bias2},
          {"variance", e.variance},
          {"signed_energy", e.signed_energy},
          {"abs_energy", e.abs_energy},
          {"per_seed_mse", e.per_seed_mse}};
}

}  // namespace

// "FLIP game (not additive per pixel): technique 0.21, oracle floor 0.02; a +0.15, b +0.04"; "" without.
std::string flip_line(const Attribution& a, const RoiAttribution& r) {
  if (r.flip.empty()) return "";
  std::string bars;
  for (size_t i = 0; i < a.stages.size(); ++i)
    bars += fmt::format("{}{} {:+.4f}", i ? ", " : "", a.stages[i], r.flip_shapley[i]);
  return fmt::format("FLIP game (its own: FLIP is not additive per pixel): technique {:.4f}, oracle floor {:.4f}; {}",
                     r.flip.front(), r.flip.back(), bars);
}

std::string mask_names(const std::vector<std::string>& stages, uint32_t mask) {
  std::string s;
  for (size_t i = 0; i < stages.size(); ++i)
    if (mask & (1u << i)) s += (s.empty() ? "" : ", ") + stages[i];
  return s.empty() ? "none" : s;
}

std::string format_table(const Attribution& a, const ReportContext& ctx) {
  std::string out = fmt::format("\n{} {} {} ({}; {} seeds, {} renders, exact Shapley over 2^{} subsets)\n",
                                ctx.case_name, ctx.row, ctx.preset, ctx.aov, a.seeds, a.renders, a.stages.size());
  for (const RoiAttribution& r : a.rois) {
    const double gap = r.none.mse - r.all.mse;
    out += fmt::format("ROI {}: error (linear MSE) {:.4g} = bias^2 {:.4g} + variance {:.4g}; energy signed {:+.1f}%, "
                       "absolute {:.1f}%\n",
                       r.roi, r.none.mse, r.none.bias2, r.none.variance, 100 * r.none.signed_energy,
                       100 * r.none.abs_energy);
    out += fmt::format("  oracle floor {:.4g} (energy {:+.1f}%); reference noise floor {:.3g}, differences below {:.3g} "
                       "not resolved{}\n",
                       r.all.mse, 100 * r.all.signed_energy, r.noise_floor, 3 * r.noise_floor,
                       r.floor_disagrees ? "; the oracle floor sits above it: oracles and reference disagree" : "");
    out += fmt::format("  {:<12} {:>7} {:>10} {:>10} {:>10} {:>9} {:>8} {:>10} {:>10}\n", "stage", "share", "removed",
                       "bias^2", "variance", "+-95%", "energy", "alone", "last");
    for (const StageInfo& s : ctx.stages) {
      const StageBar* b = bar_of(r, s.name);
      if (!b) {
        out += fmt::format("  {:<12} {} ({})\n", s.name, s.oracle.empty() ? "no oracle yet" : s.oracle,
                           fmt::join(s.passes, ", "));
        continue;
      }
      out += fmt::format("  {:<12} {:>7} {:>10.4g} {:>10.4g} {:>10.4g} {:>9.2g} {:>+7.1f}% {:>10.4g} {:>10.4g}{}\n",
                         s.name, share(b->shapley, gap), b->shapley, b->bias_removed, b->variance_removed, b->ci95,
                         100 * b->signed_energy, b->pair.alone, b->pair.last, b->resolved ? "" : "  not resolved");
    }
    out += r.largest >= 0 ? fmt::format("  largest share: {}\n", r.stages[size_t(r.largest)].stage)
                          : std::string("  largest share: not resolved (within 3x the noise floor of the next)\n");
    if (!r.flip.empty()) out += "  " + flip_line(a, r) + "\n";
  }
  return out;
}

nlohmann::json to_json(const Attribution& a, const ReportContext& ctx) {
  nlohmann::json j{{"case", ctx.case_name}, {"row", ctx.row},   {"preset", ctx.preset}, {"aov", ctx.aov},
                   {"device", ctx.device},  {"seeds", a.seeds}, {"renders", a.renders}, {"exact", a.exact},
                   {"game_stages", a.stages}};
  for (const StageInfo& s : ctx.stages) j["stages"].push_back({{"name", s.name}, {"passes", s.passes}, {"oracle", s.oracle}});
  for (const RoiAttribution& r : a.rois) {
    nlohmann::json jr{{"roi", r.roi},
                      {"technique", error_json(r.none)},
                      {"oracle_floor", error_json(r.all)},
                      {"noise_floor", r.noise_floor},
                      {"floor_disagrees", r.floor_disagrees},
                      {"largest", r.largest >= 0 ? nlohmann::json(r.stages[size_t(r.largest)].stage) : nlohmann::json()}};
    for (const StageBar& b : r.stages)
      jr["bars"].push_back({{"stage", b.stage},
                            {"shapley", b.shapley},
                            {"bias_removed", b.bias_removed},
                            {"variance_removed", b.variance_removed},
                            {"ci95", b.ci95},
                            {"signed_energy", b.signed_energy},
                            {"alone", b.pair.alone},
                            {"last", b.pair.last},
                            {"resolved", b.resolved}});
    for (size_t m = 0; m < r.subsets.size(); ++m)
      jr["subsets"].push_back({{"oracles", mask_names(a.stages, uint32_t(m))}, {"error", error_json(r.subsets[m])}});
    if (!r.flip.empty()) {
      nlohmann::json bars = nlohmann::json::object();
      for (size_t i = 0; i < a.stages.size(); ++i) bars[a.stages[i]] = r.flip_shapley[i];
      jr["flip_game"] = {{"note", "FLIP is not additive per pixel: its own game, not a part of the MSE bars"},
                         {"technique", r.flip.front()},
                         {"oracle_floor", r.flip.back()},
                         {"subsets", r.flip},
                         {"shapley", bars}};
    }
    j["rois"].push_back(jr);
  }
  return j;
}

std::string waterfalls(const Attribution& a) {
  std::string body;
  for (const RoiAttribution& r : a.rois) {
    const size_t bars = r.stages.size() + 2;
    const double w = 90.0 * double(bars) + 80, h = 260, top = 20, base = 220;
    double hi = r.none.mse;
    double level = r.none.mse;
    for (const StageBar& b : r.stages) {  // a negative bar climbs above the technique's error
      level -= b.shapley;
      hi = std::max(hi, level);
    }
    hi = std::max({hi, r.all.mse, 3 * r.noise_floor, 1e-30});
    auto y = [&](double v) { return base - (base - top) * v / hi; };
    std::string svg = fmt::format("<svg width='{:.0f}' height='{:.0f}' xmlns='http://www.w3.org/2000/svg' "
                                  "font-family='sans-serif' font-size='11'>",
                                  w, h);
    auto rect = [&](size_t i, double from, double to, const char* fill) {
      const double y0 = y(std::max(from, to)), y1 = y(std::min(from, to));
      svg += fmt::format("<rect x='{:.0f}' y='{:.1f}' width='60' height='{:.1f}' fill='{}'/>", 60 + 90.0 * double(i), y0,
                         std::max(y1 - y0, 0.5), fill);
    };
    auto label = [&](size_t i, const std::string& name, const std::string& value) {
      svg += fmt::format("<text x='{:.0f}' y='{:.0f}' text-anchor='middle'>{}</text>"
                         "<text x='{:.0f}' y='{:.0f}' text-anchor='middle'>{}</text>",
                         90 + 90.0 * double(i), base + 14, name, 90 + 90.0 * double(i), base + 28, value);
    };
    rect(0, 0, r.none.mse, "#555");
    label(0, "technique", fmt::format("{:.3g}", r.none.mse));
    level = r.none.mse;
    const double gap = r.none.mse - r.all.mse;
    for (size_t i = 0; i < r.stages.size(); ++i) {
      const StageBar& b = r.stages[i];
      const double after_bias = level - b.bias_removed;
      rect(i + 1, level, after_bias, b.resolved ? "#c0392b" : "#bbb");
      rect(i + 1, after_bias, level - b.shapley, b.resolved ? "#f1948a" : "#ddd");
      const double mid = level - b.shapley;
      svg += fmt::format("<line x1='{0:.0f}' x2='{0:.0f}' y1='{1:.1f}' y2='{2:.1f}' stroke='black'/>",
                         90 + 90.0 * double(i + 1), y(mid + b.ci95), y(mid - b.ci95));
      label(i + 1, b.stage, b.resolved ? share(b.shapley, gap) : "not resolved");
      level = mid;
    }
    rect(bars - 1, 0, r.all.mse, "#2e86c1");
    label(bars - 1, "oracle floor", fmt::format("{:.3g}", r.all.mse));
    svg += fmt::format("<line x1='50' x2='{:.0f}' y1='{:.1f}' y2='{:.1f}' stroke='#2e86c1' stroke-dasharray='4 3'/>",
                       w - 10, y(3 * r.noise_floor), y(3 * r.noise_floor));
    svg += "</svg>";
    body += fmt::format("<h2>{}</h2><p>error {:.4g} (bias&sup2; {:.4g}, variance {:.4g}; energy {:+.1f}% signed, "
                        "{:.1f}% absolute); oracle floor {:.4g}; dashed: 3x the reference noise floor {:.3g}</p>{}",
                        r.roi, r.none.mse, r.none.bias2, r.none.variance, 100 * r.none.signed_energy,
                        100 * r.none.abs_energy, r.all.mse, r.noise_floor, svg);
    if (!r.flip.empty()) body += "<p>" + flip_line(a, r) + "</p>";
  }
  return body;
}

std::string html_page(const Attribution& a, const ReportContext& ctx, const std::string& body) {
  std::string stages;
  for (const StageInfo& s : ctx.stages)
    stages += fmt::format("<li><b>{}</b> ({}): {}</li>", s.name, fmt::join(s.passes, ", "),
                          s.oracle.empty() ? "no oracle yet: not in the game" : s.oracle);
  return fmt::format("<!doctype html><html><head><meta charset='utf-8'><title>attribution {0} {1}</title></head>"
                     "<body style='font-family:sans-serif'><h1>Error attribution: {0}, {1} {2}</h1>"
                     "<p>{3}, linear HDR MSE against the reference; {4} seeds; exact Shapley values over 2^{5} "
                     "subsets of oracles; each bar: bias&sup2; removed (dark), variance removed (light), 95% interval "
                     "over seeds (whisker); grey: not resolved (below 3x the reference noise floor).</p><ul>{6}</ul>{7}"
                     "</body></html>\n",
                     ctx.case_name, ctx.row, ctx.preset, ctx.aov, a.seeds, a.stages.size(), stages, body);
}

std::string waterfall_html(const Attribution& a, const ReportContext& ctx) { return html_page(a, ctx, waterfalls(a)); }

}  // namespace gib::attribution
