#include "harness/report.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "harness/image_io.h"
#include "metrics/colormap.h"
#include "metrics/image_metrics.h"
#include "harness/report_assets.h"

namespace fs = std::filesystem;

namespace gib {

std::string base64(const void* data, size_t bytes) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const uint8_t*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  for (size_t i = 0; i < bytes; i += 3) {
    uint32_t v = uint32_t(p[i]) << 16;
    if (i + 1 < bytes) v |= uint32_t(p[i + 1]) << 8;
    if (i + 2 < bytes) v |= p[i + 2];
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += i + 1 < bytes ? kTable[(v >> 6) & 63] : '=';
    out += i + 2 < bytes ? kTable[v & 63] : '=';
  }
  return out;
}

namespace {

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  fs::path tmp = path.parent_path() / ("." + path.filename().string() + ".tmp");
  {
    std::ofstream out(tmp);
    out << text;
    if (!out) throw std::runtime_error(fmt::format("{}: write failed", path.string()));
  }
  fs::rename(tmp, path);
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

void write_report_image(const std::string& stem, const FloatImage& img) {
  write_png_preview(stem + ".png", img);
  std::vector<float> rgb(img.pixel_count() * 3);
  for (size_t i = 0; i < img.pixel_count(); ++i)
    for (uint32_t c = 0; c < 3; ++c) rgb[i * 3 + c] = img.pixels[i * img.channels + std::min(c, img.channels - 1)];
  std::string id = fs::path(stem).filename().string();
  write_text(stem + ".js", fmt::format("(window.GIB_IMG=window.GIB_IMG||{{}})[\"{}\"]={{w:{},h:{},data:\"{}\"}};\n", id,
                                       img.width, img.height, base64(rgb.data(), rgb.size() * 4)));
}

void write_report_error_map(const std::string& stem, const FloatImage& error_map) {
  // Linear magma, so the preview writer's sRGB encode gives the colour map's display values.
  write_png_preview(stem + ".png", magma_error_map(error_map, true));
}

nlohmann::json row_to_json(const ResultRow& r) {
  nlohmann::json m = nlohmann::json::object();
  for (auto& [k, v] : r.metrics) m[k] = finite_or_null(v);
  nlohmann::json passes = nlohmann::json::array();
  for (auto& p : r.plan.passes) {
    nlohmann::json pj{{"name", p.name}, {"status", p.runs ? "ran" : "culled"}, {"reason", p.reason}};
    for (auto& s : r.passes)
      if (s.name == p.name) pj.update({{"ms", s.median_ms}, {"min_ms", s.min_ms}, {"max_ms", s.max_ms}});
    passes.push_back(pj);
  }
  nlohmann::json checks = nlohmann::json::array();
  for (auto& c : r.checks) {
    nlohmann::json cj{{"metric", c.metric}, {"against", c.against}, {"roi", c.roi}, {"value", finite_or_null(c.value)},
                      {"pass", c.pass}, {"skipped", c.skipped}, {"message", c.message}};
    if (c.max) cj["max"] = *c.max;
    if (c.min) cj["min"] = *c.min;
    checks.push_back(cj);
  }
  nlohmann::json row{{"case", r.case_name}, {"technique", r.technique}, {"preset", r.preset}, {"kind", r.kind},
                     {"negative_control", r.control_name}, {"why", r.control_why}, {"options", r.options},
                     {"status", r.status}, {"messages", r.messages}, {"metrics", m}, {"checks", checks},
                     {"gpu_ms", r.gpu_ms}, {"passes", passes}, {"device", r.device}, {"image", r.image_id},
                     {"reference_image", r.reference_id}, {"golden_class", r.golden_class},
                     {"resource_bytes", r.plan.total_bytes()}, {"texture_bytes", r.texture_bytes},
                     {"wall_s", r.wall_s}};
  if (!r.views.empty()) {
    row["views"] = nlohmann::json::array();
    for (auto& [name, id] : r.views) row["views"].push_back({{"name", name}, {"image", id}});
  }
  if (!r.printouts.empty()) {
    row["printouts"] = nlohmann::json::array();
    for (auto& [name, text] : r.printouts) row["printouts"].push_back({{"name", name}, {"text", text}});
  }
  if (!r.timing.frames.empty()) {  // where gpu_ms and the pass times come from
    const perf::Summary f = r.timing.frame();
    row["timing"] = {{"frames", r.timing.frames.size()}, {"warmup", r.timing.warmup}, {"source", r.timing.source},
                     {"scan_free", r.timing.scan_free()}, {"scan_dispatches", r.timing.scan_dispatches},
                     {"frame_ms", {{"median", f.median}, {"q1", f.q1}, {"q3", f.q3}, {"min", f.min}, {"max", f.max}}},
                     {"frame_samples_ms", r.timing.frame_ms()}};
    if (r.timing.clock.measured())
      row["timing"]["clock"] = r.timing.clock.to_json();
  }
  if (!r.curve.empty()) {
    nlohmann::json curve = nlohmann::json::array();
    for (double v : r.curve) curve.push_back(finite_or_null(v));
    row["curve"] = curve;
    row["curve_target"] = r.curve_target;
  }
  if (r.eval_frames.size() > 1) row["eval_frames"] = r.eval_frames;
  if (r.scanned) {
    // Per (pass, resource) with any offender: counts over all frames and where it first was.
    nlohmann::json res = nlohmann::json::array();
    for (auto& t : r.stability.targets) {
      uint64_t nan = t.count[size_t(StabilityCategory::nan)];
      uint64_t inf = t.count[size_t(StabilityCategory::pos_inf)] + t.count[size_t(StabilityCategory::neg_inf)];
      uint64_t neg = t.count[size_t(StabilityCategory::negative)];
      uint64_t above = t.count[size_t(StabilityCategory::above_max)];
      uint64_t saturated = t.count[size_t(StabilityCategory::saturated)];
      if (!(nan || inf || neg || above || saturated)) continue;
      nlohmann::json e{{"pass", t.pass},         {"resource", t.resource}, {"nan", nan},
                       {"inf", inf},             {"negative", neg},        {"above_max", above},
                       {"saturated", saturated}, {"max_seen", finite_or_null(t.max_seen)}};
      const StabilityRecord* first = nullptr;
      for (auto& rec : r.stability.records)
        if (rec.pass == t.pass && rec.resource == t.resource) { first = &rec; break; }
      if (first) {
        e["first_frame"] = first->first_frame;
        e["first_at"] = first->buffer ? fmt::format("element {}", first->first_x)
                                      : fmt::format("({}, {})", first->first_x, first->first_y);
      }
      res.push_back(e);
    }
    row["stability"] = {{"scanned", true}, {"frames", r.stability.frames},
                        {"targets", r.stability.targets.size()}, {"resources", res},
                        {"first_offenders", r.stability.first_offender_lines()}};
  }
  return row;
}

nlohmann::json suite_to_json(const SuiteResult& suite) {
  nlohmann::json j;
  j["device"] = {{"name", suite.device.name}, {"type", suite.device.type}, {"driver", suite.device.driver_name},
                 {"driver_info", suite.device.driver_info}, {"class", suite.device_class},
                 {"golden_class", suite.golden_class}, {"tier", suite.tier}};
  if (!suite.references.empty()) j["references"] = suite.references;
  j["psnr_definition"] = metrics::psnr_description();
  if (!suite.shard.is_null()) j["shard"] = suite.shard;
  j["case_errors"] = suite.case_errors;
  auto& rows = j["results"] = nlohmann::json::array();
  for (auto& r : suite.rows) rows.push_back(row_to_json(r));
  return j;
}

nlohmann::json cases_to_json(const std::vector<Case>& cases) {
  nlohmann::json case_info = nlohmann::json::array();
  for (auto& c : cases) {
    nlohmann::json rois = nlohmann::json::array();
    for (auto& r : c.rois) rois.push_back({{"name", r.name}, {"x0", r.x0}, {"y0", r.y0}, {"x1", r.x1}, {"y1", r.y1}});
    case_info.push_back({{"name", c.name}, {"description", c.description}, {"width", c.width}, {"height", c.height},
                         {"output", c.output}, {"rois", rois}});
  }
  return case_info;
}

void write_suite_outputs(const std::string& out_dir, const SuiteResult& suite, const std::vector<Case>& cases) {
  nlohmann::json j = suite_to_json(suite);
  j["cases"] = cases_to_json(cases);
  write_report_files(out_dir, j);
}

void write_report_files(const std::string& out_dir, const nlohmann::json& j) {
  fs::path out(out_dir);
  write_text(out / "results.json", j.dump(2) + "\n");
  write_text(out / "results.js", "window.GIB_RESULTS=" + j.dump() + ";\n");

  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n";
  for (auto& c : j["cases"]) {
    const std::string name = c.value("name", "");
    std::string body;
    int tests = 0, fails = 0;
    for (auto& r : j["results"]) {
      if (r.value("case", "") != name) continue;
      ++tests;
      const std::string status = r.value("status", "error");
      std::vector<std::string> messages = r.value("messages", std::vector<std::string>{});
      std::string test = r.value("kind", "") == "negative_control" ? "negative:" + r.value("negative_control", "")
                                                                    : r.value("technique", "") + "." + r.value("preset", "");
      body += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3f}\">", xml_escape(name),
                          xml_escape(test), r.value("wall_s", 0.0));
      if (status == "known_failure" || status == "skipped" || status == "not_run") {
        body += fmt::format("<skipped message=\"{}\"/>", xml_escape(messages.empty() ? status : messages[0]));
      } else if (status != "pass") {
        ++fails;
        std::string msg;
        for (auto& m : messages) msg += m + "\n";
        body += fmt::format("<failure message=\"{}\">{}</failure>", xml_escape(messages.empty() ? "failed" : messages[0]),
                            xml_escape(msg));
      }
      body += "</testcase>\n";
    }
    for (auto& e : j["case_errors"]) {
      const std::string text = e.get<std::string>();
      if (text.rfind(name + ":", 0) != 0) continue;
      ++tests;
      ++fails;
      body += fmt::format("    <testcase classname=\"{}\" name=\"case\"><error message=\"{}\"/></testcase>\n",
                          xml_escape(name), xml_escape(text));
    }
    xml += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\">\n{}  </testsuite>\n", xml_escape(name),
                       tests, fails, body);
  }
  xml += "</testsuites>\n";
  write_text(out / "junit.xml", xml);

  // The report: static assets compiled into the binary; data from results.js and img/*.js.
  std::string img_scripts;
  std::set<std::string> ids;
  for (auto& r : j["results"]) {
    ids.insert(r.value("image", ""));
    ids.insert(r.value("reference_image", ""));
    if (r.contains("views"))
      for (auto& v : r["views"]) ids.insert(v.value("image", ""));
  }
  for (auto& id : ids)
    if (!id.empty() && fs::exists(out / "img" / (id + ".js")))
      img_scripts += fmt::format("<script src=\"img/{}.js\"></script>\n", id);
  std::string html = kReportHtml;
  auto pos = html.find("<!--GIB_IMAGE_SCRIPTS-->");
  if (pos != std::string::npos) html.replace(pos, std::string("<!--GIB_IMAGE_SCRIPTS-->").size(), img_scripts);
  write_text(out / "index.html", html);
  write_text(out / "report.js", kReportJs);
  write_text(out / "report.css", kReportCss);
}

void print_suite_table(const nlohmann::json& j) {
  auto num = [](const nlohmann::json& m, const char* k, const char* f) {
    if (!m.contains(k)) return std::string("-");
    if (m[k].is_null()) return std::string("inf");
    return fmt::format(fmt::runtime(f), m[k].get<double>());
  };
  fmt::print("{:<20} {:<22} {:<8} {:>9} {:>9} {:>9} {:>10} {:>8}  {}\n", "case", "technique", "preset", "FLIP ref",
             "PSNR ref", "FLIP gold", "GPU ms", "wall s", "status");
  for (auto& r : j["results"]) {
    const std::string status = r.value("status", "error"), kind = r.value("kind", "");
    std::string tech = kind == "negative_control"
                           ? "!" + r.value("technique", "") + " (" + r.value("negative_control", "") + ")"
                           : r.value("technique", "");
    const nlohmann::json m = r.value("metrics", nlohmann::json::object());
    fmt::print("{:<20} {:<22} {:<8} {:>9} {:>9} {:>9} {:>10} {:>8}  {}\n", r.value("case", ""), tech,
               r.value("preset", ""), num(m, "flip_vs_reference", "{:.4f}"), num(m, "psnr_vs_reference", "{:.2f}"),
               num(m, "flip_vs_golden", "{:.4f}"),
               status == "not_run" ? "-" : fmt::format("{:.2f}", r.value("gpu_ms", 0.0)),
               status == "not_run" ? "-" : fmt::format("{:.1f}", r.value("wall_s", 0.0)), status);
    if (status == "not_run") continue;  // the summary says why
    if (status != "pass" || kind == "negative_control")
      for (auto& msg : r.value("messages", std::vector<std::string>{})) fmt::print("    {}\n", msg);
  }
  for (auto& e : j["case_errors"]) fmt::print("error: {}\n", e.get<std::string>());
}

}  // namespace gib
