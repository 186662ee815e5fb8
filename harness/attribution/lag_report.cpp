// Lag attribution's outputs (attribution_report.h): the integrated game reads like a single
// frame's (its table, JSON and waterfalls), followed by what each evaluation frame's game says.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "harness/attribution/attribution_report.h"

namespace gib::attribution {

namespace {

std::string frame_list(const std::vector<uint32_t>& frames) { return fmt::format("{}", fmt::join(frames, ", ")); }

std::string share_of(const StageBar& b, double gap) {
  if (!b.resolved) return "not resolved";
  return gap > 0 ? fmt::format("{:.1f}%", 100.0 * b.shapley / gap) : "-";
}

std::string largest_of(const RoiAttribution& r) {
  return r.largest >= 0 ? r.stages[size_t(r.largest)].stage : std::string("not resolved");
}

std::string header(const LagAttribution& a) {
  return fmt::format("lag attribution: frames {} of one run per render, each against the reference of the scene "
                     "frozen at that frame; integrated error = the mean over those frames",
                     frame_list(a.frames));
}

}  // namespace

std::string format_table(const LagAttribution& a, const ReportContext& ctx) {
  std::string out = "\n" + header(a) + "\nINTEGRATED" + format_table(a.integrated, ctx);
  out += "\nPER FRAME (bar = removed MSE, share of that frame's gap)\n";
  for (size_t r = 0; r < a.integrated.rois.size(); ++r) {
    out += fmt::format("ROI {}:\n  {:>6} {:>10} {:>8} {:>10}", a.integrated.rois[r].roi, "frame", "error", "energy",
                       "floor");
    for (const std::string& s : a.integrated.stages) out += fmt::format(" {:>22}", s);
    out += "  largest\n";
    for (size_t f = 0; f < a.frames.size(); ++f) {
      const RoiAttribution& x = a.per_frame[f].rois[r];
      const double gap = x.none.mse - x.all.mse;
      out += fmt::format("  {:>6} {:>10.4g} {:>+7.1f}% {:>10.4g}", a.frames[f], x.none.mse, 100 * x.none.signed_energy,
                         x.all.mse);
      for (const StageBar& b : x.stages)
        out += fmt::format(" {:>22}", fmt::format("{:.3g} ({})", b.shapley, share_of(b, gap)));
      out += "  " + largest_of(x) + "\n";
    }
  }
  return out;
}

nlohmann::json to_json(const LagAttribution& a, const ReportContext& ctx) {
  nlohmann::json j = to_json(a.integrated, ctx);
  nlohmann::json per_frame = nlohmann::json::array();
  for (size_t f = 0; f < a.frames.size(); ++f)
    per_frame.push_back({{"frame", a.frames[f]}, {"rois", to_json(a.per_frame[f], ctx)["rois"]}});
  j["lag"] = {{"frames", a.frames},
              {"integration", "mean over the frames of every subset's error (the top-level rois are that game)"},
              {"per_frame", per_frame}};
  return j;
}

std::string waterfall_html(const LagAttribution& a, const ReportContext& ctx) {
  std::string body = fmt::format("<p>{}.</p><h2>Integrated error</h2>{}<h2>Per frame</h2>", header(a),
                                 waterfalls(a.integrated));
  for (size_t r = 0; r < a.integrated.rois.size(); ++r) {
    body += fmt::format("<h3>{}</h3><table border='1' cellpadding='3' style='border-collapse:collapse'><tr><th>frame</th>"
                        "<th>error</th><th>energy</th><th>oracle floor</th>",
                        a.integrated.rois[r].roi);
    for (const std::string& s : a.integrated.stages) body += "<th>" + s + "</th>";
    body += "<th>largest</th></tr>";
    for (size_t f = 0; f < a.frames.size(); ++f) {
      const RoiAttribution& x = a.per_frame[f].rois[r];
      const double gap = x.none.mse - x.all.mse;
      body += fmt::format("<tr><td>{}</td><td>{:.4g}</td><td>{:+.1f}%</td><td>{:.4g}</td>", a.frames[f], x.none.mse,
                          100 * x.none.signed_energy, x.all.mse);
      for (const StageBar& b : x.stages) body += fmt::format("<td>{:.3g} ({})</td>", b.shapley, share_of(b, gap));
      body += "<td>" + largest_of(x) + "</td></tr>";
    }
    body += "</table>";
  }
  return html_page(a.integrated, ctx, body);
}

}  // namespace gib::attribution
