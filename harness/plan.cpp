#include "harness/plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

namespace gib {

std::string row_key(const std::string& case_name, const std::string& kind, const std::string& technique,
                    const std::string& preset, const std::string& control) {
  return kind == "negative_control" ? case_name + "/negative:" + control : case_name + "/" + technique + "." + preset;
}

std::string row_key_of(const nlohmann::json& row) {
  return row_key(row.value("case", ""), row.value("kind", ""), row.value("technique", ""), row.value("preset", ""),
                 row.value("negative_control", ""));
}

std::string row_seconds_path(const std::string& cases_dir) {
  return (std::filesystem::path(cases_dir) / "timings" / "lavapipe.json").string();
}

RowSeconds load_row_seconds(const std::string& cases_dir) {
  const std::string path = row_seconds_path(cases_dir);
  std::ifstream in(path);
  if (!in) return {};
  RowSeconds out;
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    for (auto& [key, v] : j.at("rows").items()) {
      if (!v.is_number() || v.get<double>() < 0)
        throw std::runtime_error(fmt::format("/rows/{}: expected seconds >= 0, got {}", key, v.dump()));
      out[key] = v.get<double>();
    }
  } catch (const std::exception& e) {
    throw CaseError(fmt::format("{}: expected {{\"rows\": {{row key: seconds}}}}, got: {}", path, e.what()));
  }
  return out;
}

void record_row_seconds(const std::string& cases_dir, const RowSeconds& rows, const std::string& how) {
  RowSeconds all = load_row_seconds(cases_dir);
  for (auto& [k, v] : rows) all[k] = std::round(v * 10.0) / 10.0;
  nlohmann::json j{{"measured", how}, {"rows", all}};
  const std::filesystem::path path = row_seconds_path(cases_dir);
  std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error(fmt::format("{}: write failed", tmp.string()));
  }
  std::filesystem::rename(tmp, path);
}

std::vector<PlannedRow> plan_suite(const std::vector<Case>& cases, const RowSeconds& recorded) {
  std::vector<PlannedRow> rows;
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    for (size_t ri = 0; ri < c.techniques.size(); ++ri) {
      const TechniqueRun& run = c.techniques[ri];
      for (auto& preset : run.presets)
        rows.push_back({row_key(c.name, "technique", run.name(), preset, ""), ci, "technique", ri, run.technique,
                        preset, "", estimated_row_seconds(c, run)});
    }
    for (size_t ni = 0; ni < c.negative_controls.size(); ++ni) {
      const NegativeControl& nc = c.negative_controls[ni];
      rows.push_back({row_key(c.name, "negative_control", nc.run.technique, "", nc.name), ci, "negative_control", ni,
                      nc.run.technique, nc.run.presets.front(), nc.name,
                      estimated_row_seconds(c, nc.run)});
    }
  }
  for (PlannedRow& r : rows)
    if (auto it = recorded.find(r.key); it != recorded.end()) r.cost = it->second;
  return rows;
}

std::vector<std::string> plan_rows(const std::vector<Case>& cases) {
  std::vector<std::string> keys;
  for (auto& r : plan_suite(cases)) keys.push_back(r.key);
  return keys;
}

const TechniqueRun& planned_run(const std::vector<Case>& cases, const PlannedRow& row) {
  const Case& c = cases.at(row.case_index);
  return row.kind == "negative_control" ? c.negative_controls.at(row.run_index).run : c.techniques.at(row.run_index);
}

namespace {

// Seconds per million pixel-frames of one lavapipe worker on one core (LP_NUM_THREADS=0, what
// -j gives each worker on a CPU device), by technique; the reference's cost is per million
// samples x pixels. Fitted to a full CI-tier run on a 2-core machine (per-row CPU seconds): the
// radiance-cache rows of extreme-range and gltf-atrium read 59-82 s per million pixel-frames,
// probe-volume 25-41, voxel-clipmap 30-41, the path tracer 9-33 per million samples x pixels
// (cornell, extreme-range, alpha-foliage's alpha-tested leaves).
double seconds_per_mpixel_frame(const std::string& technique) {
  if (technique == "radiance-cache") return 65.0;
  if (technique == "voxel-clipmap") return 38.0;
  if (technique == "probe-volume") return 30.0;
  if (technique == "gow-ragnarok") return 30.0;
  if (technique == "reference") return 20.0;
  if (technique == "deferred") return 6.0;
  return 7.0;  // direct
}
constexpr double kRenderOverheadSeconds = 2.0;  // executor, pipelines (compiled by lavapipe), images, FLIP

}  // namespace

double estimated_row_seconds(const Case& c, const TechniqueRun& run) {
  const double mpixels = double(c.width) * double(c.height) * 1e-6;
  double frames = double(run.frames ? run.frames : c.frames) + double(c.timing_frames);
  // A reference row with an spp budget: its samples (the frames split them), plus timing frames
  // of one sample each.
  if (run.technique == "reference" && run.spp) frames = double(run.spp) + double(c.timing_frames);
  const double renders = 1.0 + double(run.variants.size());
  return renders * (kRenderOverheadSeconds + frames * mpixels * seconds_per_mpixel_frame(run.technique));
}

Profile resolve_profile(const std::string& requested, bool cpu_device) {
  if (requested == "quick") return Profile::quick;
  if (requested == "full") return Profile::full;
  if (!requested.empty())
    throw std::invalid_argument(fmt::format("--profile: expected quick or full, got '{}'", requested));
  return cpu_device ? Profile::quick : Profile::full;
}

const char* profile_name(Profile p) { return p == Profile::quick ? "quick" : "full"; }

std::map<std::string, std::string> select_quick(const std::vector<Case>& cases, const std::vector<PlannedRow>& plan) {
  std::set<std::string> chosen;
  auto cheapest = [&](auto&& pred) -> const PlannedRow* {
    const PlannedRow* best = nullptr;
    for (const PlannedRow& r : plan)
      if (pred(r) && (!best || r.cost < best->cost)) best = &r;
    return best;
  };
  std::set<std::string> techniques_touched;
  for (size_t ci = 0; ci < cases.size(); ++ci)
    for (const char* kind : {"technique", "negative_control"})
      if (const PlannedRow* r = cheapest([&](const PlannedRow& p) { return p.case_index == ci && p.kind == kind; })) {
        if (r->kind == "negative_control" && r->cost > kQuickSlowRowSeconds) continue;
        chosen.insert(r->key);
        techniques_touched.insert(r->technique);
      }
  std::set<std::string> techniques;
  for (const PlannedRow& r : plan) techniques.insert(r.technique);
  for (const std::string& t : techniques)
    if (!techniques_touched.count(t))
      if (const PlannedRow* r = cheapest([&](const PlannedRow& p) { return p.technique == t; })) chosen.insert(r->key);
  std::map<std::string, std::string> left_out;
  for (size_t i = 0; i < plan.size(); ++i) {
    const PlannedRow& r = plan[i];
    if (chosen.count(r.key)) continue;
    if (i % kQuickStride == 0 && r.cost <= kQuickSlowRowSeconds) continue;
    left_out[r.key] = r.cost > kQuickSlowRowSeconds
                          ? fmt::format("not run by the quick profile: a slow row (about {:.0f} s on lavapipe); "
                                        "--profile full runs it", r.cost)
                          : fmt::format("not run by the quick profile (it runs every {}th row, each case's and each "
                                        "technique's cheapest); --profile full runs it", kQuickStride);
  }
  return left_out;
}

}  // namespace gib
