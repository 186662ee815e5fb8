#include "perf/perf.h"

#include "perf/budgets.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "perf/calibration.h"
#include "perf/calibration_shared.h"
#include "perf/frame_timing.h"
#include "perf/occupancy.h"
#include "perf/pipeline_stats.h"
#include "perf/profiles.h"
#include "perf/project_files.h"
#include "perf/stats.h"
#include "revision.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/aov.h"
#include "renderer/techniques/technique.h"

namespace gib::perf {

std::optional<double> touched_elements(const Touched& t, const std::map<std::string, double>& counters) {
  double elements = t.fixed;
  for (const Touched::Per& p : t.per) {
    const auto it = counters.find(p.counter);
    if (it == counters.end()) return std::nullopt;
    elements += p.count * it->second;
  }
  return std::max(0.0, elements);
}

uint64_t touched_bytes(const Touched& t, double elements, uint64_t resource_bytes) {
  constexpr double kSectorBytes = 32;
  const double each = t.contiguous ? double(t.element_bytes) : std::max(kSectorBytes, double(t.element_bytes));
  return uint64_t(std::min(double(resource_bytes), std::ceil(std::max(0.0, elements) * each)));
}

PassBytes pass_bytes(const Plan& plan, const PlannedPass& pass, const std::map<std::string, double>* counters) {
  PassBytes b;
  b.written = pass.bytes_written;
  for (auto& s : pass.slots) {
    const ResolvedResource* r = plan.find(s.name);
    if (!r) continue;
    const uint64_t size = r->bytes_per_copy ? r->bytes_per_copy : r->bytes;
    uint64_t moved = size;
    if (s.touched) {
      const std::optional<double> elements = counters ? touched_elements(*s.touched, *counters) : std::nullopt;
      if (elements) {
        moved = touched_bytes(*s.touched, *elements, size);
        b.sparse.push_back(fmt::format("{} {} bytes ({:.0f} elements)", s.name, moved, *elements));
      } else {
        b.unresolved.push_back(s.name);
      }
    }
    if (s.access != Access::write) b.read += moved;
    // The plan's bytes_written counts each written slot's copy (compile.cpp): the sparse one
    // moves less.
    if (s.touched && (s.access == Access::write || s.access == Access::read_write))
      b.written = b.written - r->bytes_per_copy + std::min(moved, r->bytes_per_copy);
  }
  return b;
}

BenchOutputs bench_outputs(const Technique& t, SceneFeatures features, const std::vector<std::string>& only) {
  for (const std::string& a : only)
    if (std::find(kContractAovs.begin(), kContractAovs.end(), a) == kContractAovs.end())
      throw PerfError(fmt::format("--aov {}: expected a contract AOV ({}), got '{}'", a, fmt::join(kContractAovs, ", "), a));
  BenchOutputs out;
  const std::vector<std::string> declared = contract_aov_names(t), supported = contract_aov_names(t, features);
  auto has = [](const std::vector<std::string>& v, const std::string& a) { return std::find(v.begin(), v.end(), a) != v.end(); };
  for (const std::string& a : declared) {
    if (!only.empty() && !has(only, a)) {
      out.left_out.push_back(a + " (not asked for by --aov)");
      continue;
    }
    if (!has(supported, a)) {
      out.left_out.push_back(a + " (the scene lacks the features it needs)");
      continue;
    }
    out.aovs.push_back(a);
    const std::string r = contract_resource(t, a);
    if (!has(out.resources, r)) out.resources.push_back(r);
  }
  for (const std::string& a : only)
    if (!has(declared, a)) out.left_out.push_back(a + " (not in " + t.name + "'s contract)");
  return out;
}

double parse_scale(const std::string& text) {
  double v = 0;
  unsigned a = 0, b = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &slash, &b, &extra) == 3 && slash == '/' && b)
    v = double(a) / double(b);
  else {
    try {
      size_t used = 0;
      v = std::stod(text, &used);
      if (used != text.size()) v = 0;
    } catch (const std::exception&) {
      v = 0;
    }
  }
  if (!(v > 0 && v <= 1))
    throw PerfError(fmt::format("--scale-resolution: expected a fraction in (0, 1] like 1/8 or 0.125, got '{}'", text));
  return v;
}

namespace {

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw PerfError(fmt::format("{}: cannot open", path));
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct Workload {
  uint32_t width = 0, height = 0;                 // the profiles' target resolution (or a seed table's)
  std::string seed_table;                         // "": the profiles' targets; else the table whose workload this is
  std::string technique;                          // a seed table's workload: the only technique run at it
  uint32_t run_width = 0, run_height = 0;         // what was rendered
  std::vector<const ConsoleProfile*> profiles;
  std::string name() const { return fmt::format("{}x{}", width, height); }
  std::string run_name() const { return fmt::format("{}x{}", run_width, run_height); }
  std::vector<std::string> profile_names() const {
    std::vector<std::string> n;
    for (auto* p : profiles) n.push_back(p->name);
    return n;
  }
};

// A workload at a target resolution, rendered at `scale` of it (at least 8 x 8).
Workload make_workload(uint32_t width, uint32_t height, double scale) {
  Workload w;
  w.width = width;
  w.height = height;
  w.run_width = std::max(8u, uint32_t(std::lround(width * scale)));
  w.run_height = std::max(8u, uint32_t(std::lround(height * scale)));
  return w;
}

struct PassRun {
  std::string name;
  std::vector<double> samples;   // ms per frame, every repeat
  std::vector<uint32_t> repeat;  // which repeat each sample came from
  PassBytes bytes_run, bytes_full;
  double work_scale = 1;         // bytes_full / bytes_run: the per-pass scale to the workload
  bool raster = false;           // a graphics pass: scaled by fill rate (scale_raster_to_profile)
  bool traces_rays = false;      // walks the BVH in its shaders (PassDecl::traces_rays)
  nlohmann::json counters;
  DispatchSamples dispatches;    // from the profiled frames (occupancy term); empty: not profiled
  std::vector<const Pipeline*> pipelines;  // the compute pipelines it ran (profiled frames), with their statistics
};

struct TechniqueRun {
  const Technique* technique = nullptr;
  std::string name;     // the technique's name, "+LABEL" for a --variant
  int base = -1;        // a variant: index of the plain run it is compared with
  std::map<std::string, double> variant_options;  // a variant's options (on top of the preset)
  Workload workload;
  Settings settings_run, settings_full;
  Plan plan_run, plan_full;
  BenchOutputs outputs;              // the planned contract AOVs and their resources
  std::set<std::string> aov_only;    // running passes that feed no radiance: only other AOVs
  std::vector<PassRun> passes;
  std::vector<double> frame_ms;
  std::vector<uint32_t> frame_repeat;
};

// One profiled frame's dispatches of a pass added to its samples (by record order).
void add_dispatch_samples(DispatchSamples& s, const std::vector<DispatchTiming>& frame) {
  if (s.frames++ == 0) {
    s.ms.resize(frame.size());
    s.threads.resize(frame.size());
  } else if (s.ms.size() != frame.size()) {
    s.consistent = false;
  }
  if (!s.consistent) return;
  for (size_t i = 0; i < frame.size(); ++i) {
    s.ms[i].push_back(frame[i].ms);
    s.threads[i].push_back(double(frame[i].threads));
  }
}

// Work done per frame, as the pass declares it (PassDecl::work), for reports.
nlohmann::json work_counters(const PlannedPass& pass, const Settings& s) {
  nlohmann::json c;
  c["pixels"] = double(s.width) * s.height;
  for (const WorkCounter& w : pass.work) c[w.name] = w.per_frame;
  return c;
}

Plan compile_for(const Technique& t, const Scene& scene, const Settings& s, const std::vector<std::string>& outputs) {
  std::vector<PassDecl> decls;
  for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
  return compile(decls, {scene.features(), outputs, s.width, s.height});
}

std::string fmt_ms(double ms) {
  if (!std::isfinite(ms)) return "-";
  if (ms >= 100) return fmt::format("{:.1f}", ms);
  if (ms >= 1) return fmt::format("{:.3f}", ms);
  return fmt::format("{:.4f}", ms);
}
std::string fmt_pct(double f) {
  if (!std::isfinite(f)) return "inf";
  return fmt::format("{:+.1f}%", f * 100);
}

std::string scale_text(double f) {
  double inv = 1 / f;
  if (std::fabs(inv - std::round(inv)) < 1e-9) return fmt::format("1/{}", int(std::round(inv)));
  return fmt::format("{:g}", f);
}

}  // namespace

// The column of `table` the run's settings select ("" for a one-column table, "?" when the
// technique cannot tell).
std::string seed_column(const SeedTable& table, const TechniqueRun& r) {
  if (table.column_option.empty()) return "";
  for (const TechniqueOption& o : technique_options(*r.technique))
    if (o.name == table.column_option && o.read) {
      auto it = table.column_of_value.find(o.read(r.settings_full));
      return it == table.column_of_value.end() ? "?" : it->second;
    }
  return "?";
}

// Seed comparison of one run: per table row, our scaled cost of the passes that make it up.
// `flop_by_pass`: the same scaled costs without the occupancy term (the FLOP split alone);
// `nolat_by_pass`: with the occupancy term but without its dispatch latency (perf/occupancy.h).
using CostByPass = std::map<std::string, std::map<std::string, double>>;  // profile -> pass -> ms
void add_seed_rows(const SeedTable& table, const TechniqueRun& r, const CostByPass& scaled_by_pass,
                   const CostByPass& flop_by_pass, const CostByPass& nolat_by_pass, nlohmann::json& jseed) {
  const std::string selected = seed_column(table, r);
  for (const ConsoleProfile* p : r.workload.profiles)
    for (const SeedPlatform& platform : table.platforms) {
      // A table with a column option compares the column the run's settings pick; one without
      // compares every column it holds for the profile (each its own capture).
      if (platform.profile != p->name || (!table.column_option.empty() && platform.column != selected)) continue;
      // A table at its own workload is compared only at that resolution.
      if (table.own_workload && (platform.width != r.workload.width || platform.height != r.workload.height)) continue;
      const SeedPlatform* sp = &platform;
      const std::string& column = platform.column;
      auto mine = scaled_by_pass.find(p->name);
      if (mine == scaled_by_pass.end()) continue;
      std::map<std::string, double> ours, ours_flop, ours_nolat;
      std::map<std::string, std::vector<std::string>> passes;
      std::map<std::string, bool> walks;  // a pass of the row walks the BVH in software
      const auto& flop = flop_by_pass.at(p->name);
      const auto& nolat = nolat_by_pass.at(p->name);
      for (auto& [pass, ms] : mine->second)
        if (auto k = table.pass_row.find(pass); k != table.pass_row.end()) {
          ours[k->second] += ms;
          ours_flop[k->second] += flop.at(pass);
          ours_nolat[k->second] += nolat.at(pass);
          passes[k->second].push_back(pass);
          for (const PassRun& pr : r.passes)
            if (pr.name == pass && pr.traces_rays) walks[k->second] = true;
        }
      for (auto& [row, ms] : ours) {
        auto it = sp->ms.find(row);
        if (it == sp->ms.end()) continue;
        jseed.push_back({{"table", table.name}, {"technique", r.name}, {"base_technique", r.technique->name},
                         {"column", column}, {"profile", p->name}, {"seed_key", row}, {"passes", passes[row]},
                         {"ours_ms", ms}, {"seed_ms", it->second}, {"ratio", it->second > 0 ? ms / it->second : 0.0},
                         {"ours_ms_flop_split", ours_flop[row]},
                         {"ratio_flop_split", it->second > 0 ? ours_flop[row] / it->second : 0.0},
                         {"ours_ms_no_dispatch_latency", ours_nolat[row]},
                         {"ratio_no_dispatch_latency", it->second > 0 ? ours_nolat[row] / it->second : 0.0},
                         {"resolution", {r.workload.width, r.workload.height}},
                         {"seed_resolution", {sp->width, sp->height}},
                         {"software_bvh_walk", walks[row]}});
      }
    }
}

void print_seed_comparison(const std::vector<SeedTable>& seeds, const std::vector<const Technique*>& techs,
                           const nlohmann::json& jseed) {
  for (const SeedTable& table : seeds) {
    fmt::print("\n== seed comparison: {} ({}) ==\n", table.name, table.source);
    if (table.own_workload && !table.platforms.empty())
      fmt::print("compared only at the table's own workload, {}x{} (bench runs it as an extra workload for {})\n",
                 table.platforms[0].width, table.platforms[0].height, table.technique);
    std::vector<const nlohmann::json*> rows;
    for (auto& e : jseed)
      if (e["table"] == table.name) rows.push_back(&e);
    if (rows.empty()) {
      const bool ran = std::any_of(techs.begin(), techs.end(), [&](auto* t) { return t->name == table.technique; });
      std::vector<std::string> profiles;
      for (auto& p : table.platforms)
        if (std::find(profiles.begin(), profiles.end(), p.profile) == profiles.end()) profiles.push_back(p.profile);
      fmt::print("{}: no row compared ({}; the table's profiles: {})\n", table.technique,
                 ran ? "no run at a profile the table has" : "not run", fmt::join(profiles, ", "));
      continue;
    }
    // "flop only": the ratio the FLOP / bandwidth split gives without the occupancy term; "no
    // latency": with the occupancy term but every dispatch's launch scaled by the FLOP ratio too.
    fmt::print("{:<22} {:<14} {:<12} {:<32} {:>10} {:>10} {:>8} {:>10} {:>10}  {}\n", "technique", "profile", "column",
               "seed row", "ours ms", "seed ms", "ratio", "flop only", "no latency", "our passes");
    struct Sum {
      double ours = 0, seed = 0, flop = 0, nolat = 0;
    };
    std::map<std::tuple<std::string, std::string, std::string>, Sum> sums;
    bool walk_rows = false;
    for (auto* e : rows) {
      const std::string column = (*e)["column"];
      fmt::print("{:<22} {:<14} {:<12} {:<32} {:>10} {:>10} {:>7.2f}x {:>9.2f}x {:>9.2f}x  {}{}\n",
                 (*e)["technique"].get<std::string>(), (*e)["profile"].get<std::string>(), column.empty() ? "-" : column,
                 (*e)["seed_key"].get<std::string>(), fmt_ms((*e)["ours_ms"]), fmt_ms((*e)["seed_ms"]),
                 (*e)["ratio"].get<double>(), (*e)["ratio_flop_split"].get<double>(),
                 e->value("ratio_no_dispatch_latency", (*e)["ratio"].get<double>()),
                 fmt::join((*e)["passes"].get<std::vector<std::string>>(), "+"),
                 e->value("software_bvh_walk", false) ? " [software BVH walk]" : "");
      walk_rows |= e->value("software_bvh_walk", false);
      auto& s = sums[{(*e)["technique"], (*e)["profile"], column}];
      s.ours += (*e)["ours_ms"].get<double>();
      s.seed += (*e)["seed_ms"].get<double>();
      s.flop += (*e)["ours_ms_flop_split"].get<double>();
      s.nolat += e->value("ours_ms_no_dispatch_latency", (*e)["ours_ms"].get<double>());
    }
    for (auto& [k, s] : sums) {
      const SeedPlatform* sp = table.find(std::get<1>(k), std::get<2>(k));
      const bool total = sp && !table.total_row.empty() && sp->ms.count(table.total_row);
      fmt::print("{:<22} {:<14} {:<12} {:<32} {:>10} {:>10} {:>7.2f}x {:>9.2f}x {:>9.2f}x  (seed {} {} ms)\n",
                 std::get<0>(k), std::get<1>(k), std::get<2>(k).empty() ? "-" : std::get<2>(k), "sum of matched rows",
                 fmt_ms(s.ours), fmt_ms(s.seed), s.seed > 0 ? s.ours / s.seed : 0.0, s.seed > 0 ? s.flop / s.seed : 0.0,
                 s.seed > 0 ? s.nolat / s.seed : 0.0,
                 table.total_row.empty() ? "total" : table.total_row,
                 total ? fmt_ms(sp->ms.at(table.total_row)) : "-");
    }
    if (walk_rows)
      fmt::print("[software BVH walk]: the row's passes walk the BVH as shader code on this device (no ray queries); "
                 "the seed's platforms walk it on RT hardware, which the FLOP split does not model: those ratios "
                 "compare a software walk with fixed-function units\n");
    // A table with columns (VRCS off / on): where both were measured for one technique and
    // profile, our change per row next to the seed's: the shape of the gains.
    if (table.column_of_value.size() < 2) continue;
    const std::string off = table.column_of_value.begin()->second, on = table.column_of_value.rbegin()->second;
    bool header = false;
    for (auto* a : rows)
      for (auto* b : rows) {
        if ((*a)["column"] != off || (*b)["column"] != on || (*a)["base_technique"] != (*b)["base_technique"] ||
            (*a)["profile"] != (*b)["profile"] || (*a)["seed_key"] != (*b)["seed_key"])
          continue;
        if (!header) {
          fmt::print("{} -> {} per row ({} vs {}):\n{:<32} {:>10} {:>10}\n", off, on, (*a)["technique"].get<std::string>(),
                     (*b)["technique"].get<std::string>(), "seed row", "ours", "seed");
          header = true;
        }
        const double ours = (*b)["ours_ms"].get<double>() / (*a)["ours_ms"].get<double>() - 1;
        const double seed = (*b)["seed_ms"].get<double>() / (*a)["seed_ms"].get<double>() - 1;
        fmt::print("{:<32} {:>10} {:>10}\n", (*a)["seed_key"].get<std::string>(), fmt_pct(ours), fmt_pct(seed));
      }
    if (!header)
      fmt::print("(run both columns, e.g. --variant {}:{}=..., to compare the {} -> {} change per row)\n", off,
                 table.column_option, off, on);
  }
}

// AC Shadows' alpha-test cost table: variants that change only the alpha strategy, against their
// plain run (the exact test, unless the preset says otherwise); printed, and returned as JSON.
nlohmann::json alpha_cost_comparison(const std::vector<TechniqueRun>& runs, const AlphaCostTable& alpha_costs) {
  nlohmann::json jalpha = nlohmann::json::array();
  bool alpha_header = false;
  for (auto& r : runs) {
    if (r.base < 0 || r.variant_options.empty()) continue;
    const bool only_alpha = std::all_of(r.variant_options.begin(), r.variant_options.end(), [](auto& kv) {
      return kv.first == "alpha_strategy" || kv.first == "alpha_any_hit_limit";
    });
    const TechniqueRun& b = runs[size_t(r.base)];
    if (!only_alpha || b.settings_full.alpha.strategy != AlphaStrategy::test || b.settings_full.alpha.any_hit_limit != 0)
      continue;
    const auto key = std::make_pair(static_cast<uint32_t>(r.settings_full.alpha.strategy), r.settings_full.alpha.any_hit_limit);
    auto seed = alpha_costs.relative.find(key);
    // The plain run's costliest pass: where the traversals are.
    const PassRun* top = nullptr;
    for (auto& bp : b.passes)
      if (!top || median_of(bp.samples) > median_of(top->samples)) top = &bp;
    double pass_ratio = 0;
    if (top)
      for (auto& vp : r.passes)
        if (vp.name == top->name) pass_ratio = median_of(vp.samples) / median_of(top->samples);
    const double frame_ratio = median_of(r.frame_ms) / median_of(b.frame_ms);
    if (!alpha_header) {
      fmt::print("\n== seed comparison: ac_shadows_alpha_test_cost ({}): cost relative to the exact alpha test ==\n",
                 alpha_costs.source);
      fmt::print("{:<34} {:<26} {:>8} {:>8} {:>8}  {}\n", "variant", "costliest pass", "pass", "frame", "seed",
                 "seed row");
      alpha_header = true;
    }
    fmt::print("{:<34} {:<26} {:>8.3f} {:>8.3f} {:>8}  {}\n", r.name, top ? top->name : "-", pass_ratio, frame_ratio,
               seed == alpha_costs.relative.end() ? "-" : fmt::format("{:.2f}", seed->second.second),
               seed == alpha_costs.relative.end() ? "(none: alpha ignored or another setting)" : seed->second.first);
    jalpha.push_back({{"variant", r.name}, {"base", b.name}, {"pass", top ? top->name : ""}, {"pass_ratio", pass_ratio},
                      {"frame_ratio", frame_ratio},
                      {"seed_row", seed == alpha_costs.relative.end() ? "" : seed->second.first},
                      {"seed_ratio", seed == alpha_costs.relative.end() ? 0.0 : seed->second.second}});
  }

  return jalpha;
}

int cmd_bench(const BenchOptions& o) {
  const std::string data = find_data_dir(o.data_dir);
  const std::string profiles_path = data + "/console-profiles.json", seeds_path = data + "/seed-timings.json";
  auto all_profiles = load_profiles(profiles_path);
  auto profiles = select_profiles(all_profiles, o.profiles);
  const std::vector<SeedTable> seeds = load_seed_tables(seeds_path);
  const AlphaCostTable alpha_costs = load_alpha_cost_table(seeds_path);  // before the runs: a bad table fails first
  // Per-category budgets (data/budgets.json); a data folder without the file prints no trees.
  std::optional<Budgets> budgets;
  if (std::ifstream(data + "/budgets.json").good()) budgets = load_budgets(data + "/budgets.json");
  else fmt::print("note: no {}/budgets.json: no budget trees\n", data);
  std::vector<std::pair<std::string, BudgetTree>> budget_trees;

  std::vector<const Technique*> techs;
  if (o.techniques.empty())
    for (auto& t : techniques()) techs.push_back(&t);
  else
    for (auto& n : o.techniques) techs.push_back(&find_technique(n));
  const std::string scene_path = resolve_case_scene(o.case_name);
  // Before any GPU work: a missing default history folder fails now, not after the runs.
  const std::string hist = o.no_history ? "" : o.history.empty() ? default_history_path() : o.history;
  Scene scene = load_scene(scene_path);

  // Pipeline statistics on: each pass's registers and shared memory where the driver says them.
  auto gpu = Gpu::create({.device = o.device, .validate = false, .pipeline_statistics = true});
  const DeviceInfo& dev = gpu->info();
  const bool cpu = dev.is_software();
  const double scale = o.scale_resolution.empty() ? (cpu ? 0.125 : 1.0) : parse_scale(o.scale_resolution);
  const uint32_t frames = o.frames ? o.frames : (cpu ? 5 : 30);
  const uint32_t warmup = o.warmup ? o.warmup : (cpu ? 1 : 5);
  const uint32_t repeats = std::max(1u, o.repeats);

  fmt::print("device: {} ({}, {} {}, subgroup {})\n", dev.name, dev.type, dev.driver_name, dev.driver_info,
             dev.subgroup_size);
  fmt::print("calibrating (median of {} repeats)...\n", o.calibration_repeats);
  std::fflush(stdout);
  Calibration cal = calibrate(*gpu, o.calibration_repeats);
  DeviceThroughput thr = cal.throughput;
  thr.resident_threads = dev.resident_threads;
  // The occupancy term (perf/occupancy.h) needs the device's resident threads, timestamps per
  // dispatch (a GPU) and thread counts at the profile's workload (no --scale-resolution).
  std::string occupancy_off;
  if (cpu) occupancy_off = "a CPU device: no timestamps per dispatch";
  else if (!dev.resident_threads) occupancy_off = "the driver does not report resident threads";
  else if (scale != 1) occupancy_off = "--scale-resolution < 1: thread counts are not the workload's";
  const uint32_t profile_frames = occupancy_off.empty() ? 3 : 0;
  if (occupancy_off.empty())
    fmt::print("occupancy: {} threads resident ({}); {} profiled frames per repeat after the timed ones\n",
               dev.resident_threads, dev.residency_source, profile_frames);
  else
    fmt::print("occupancy term off ({}): compute time scales by the FLOP ratio alone\n", occupancy_off);
  fmt::print("calibration: FP32 {:.1f} GFLOP/s (the faster of two FMA kernels, {}: vec4 chains {:.1f}, scalar chains "
             "{:.1f}, ratio {:.3f}), copy bandwidth {:.1f} GB/s ({:.0f} MiB moved/dispatch)\n",
             thr.fp32_gflops, cal.timing, cal.fma_gflops, cal.fma_scalar_gflops,
             cal.fma_scalar_gflops > 0 ? cal.fma_gflops / cal.fma_scalar_gflops : 0.0, thr.bandwidth_gbs,
             cal.copy_bytes / 1048576.0);
  if (cal.dispatch_latency_ms > 0)
    fmt::print("calibration: dispatch latency {:.2f} us (an empty one-group dispatch behind a barrier, chains of {}; "
               "scaled as a dispatch that fills neither GPU, perf/occupancy.h)\n",
               cal.dispatch_latency_ms * 1e3, glsl::kCalibDispatchChain);
  fmt::print("calibration: raster fill {:.2f} Gpixel/s ({} full-screen layers at {}x{}, D32 test + rg32_uint write)\n",
             thr.fill_gpix, cal.raster_layers, cal.raster_width, cal.raster_height);

  // Workloads: one per distinct target resolution; profiles sharing one share the measurement.
  std::vector<Workload> workloads;
  for (auto& p : profiles) {
    auto it = std::find_if(workloads.begin(), workloads.end(),
                           [&](auto& w) { return w.width == p.width && w.height == p.height; });
    if (it == workloads.end()) {
      workloads.push_back(make_workload(p.width, p.height, scale));
      it = workloads.end() - 1;
    }
    it->profiles.push_back(&p);
  }
  // A seed table at its own resolution (GoW Ragnarok: PS5 at 4K, where the ps5 profile targets
  // 2560x1440): an extra workload for the table's technique and the selected profiles it names.
  for (const SeedTable& table : seeds) {
    if (!table.own_workload ||
        std::none_of(techs.begin(), techs.end(), [&](auto* t) { return t->name == table.technique; }))
      continue;
    for (const SeedPlatform& sp : table.platforms) {
      auto p = std::find_if(profiles.begin(), profiles.end(), [&](auto& x) { return x.name == sp.profile; });
      if (p == profiles.end() || (p->width == sp.width && p->height == sp.height)) continue;
      auto it = std::find_if(workloads.begin(), workloads.end(), [&](auto& w) {
        return w.seed_table == table.name && w.width == sp.width && w.height == sp.height;
      });
      if (it == workloads.end()) {
        Workload w = make_workload(sp.width, sp.height, scale);
        w.seed_table = table.name;
        w.technique = table.technique;
        workloads.push_back(w);
        it = workloads.end() - 1;
      }
      if (std::find(it->profiles.begin(), it->profiles.end(), &*p) == it->profiles.end()) it->profiles.push_back(&*p);
    }
  }
  for (auto& w : workloads)
    if (!w.seed_table.empty())
      fmt::print("seed table {}: {} also runs at {} for {} (the table's workload; the profile's target is the other "
                 "run)\n",
                 w.seed_table, w.technique, w.name(), fmt::join(w.profile_names(), ", "));
  fmt::print("case: {} (scene {}), preset {}, {} warm-up + {} timed frames x {} repeats; timing: {}\n", o.case_name,
             scene_path, o.preset, warmup, frames, repeats, cpu ? "host clock per pass (CPU device)" : "GPU timestamps");
  if (scale != 1)
    fmt::print("resolution scale {}: passes run at {} of each profile's pixels; each pass's time is scaled up by the "
               "ratio of the bytes it moves at the full resolution to those at the run resolution (= the pixel "
               "ratio for passes whose resources follow the render size, 1 for fixed-size passes)\n",
               scale_text(scale), scale_text(scale * scale));

  // --variant: parsed up front (option names are checked against each technique below).
  std::vector<BenchVariant> variants;
  for (const auto& v : o.variants) variants.push_back(parse_variant(v));

  // Runs: each technique and workload, then its variants (base = the plain run's index);
  // timed repeat-major below, so the two halves of the noise floor are apart in time.
  std::vector<TechniqueRun> runs;
  std::set<std::string> skipped_variants;  // "label/technique", noted once
  for (auto* t : techs) {
    const BenchOutputs outs = bench_outputs(*t, scene.features(), o.aovs);
    if (outs.aovs.empty()) {
      fmt::print("{}: nothing to time (no planned AOV: {})\n", t->name, fmt::join(outs.left_out, ", "));
      continue;
    }
    fmt::print("{}: planned AOVs {}{}{}\n", t->name, fmt::join(outs.aovs, ", "), outs.left_out.empty() ? "" : "; left out: ",
               fmt::join(outs.left_out, ", "));
    for (auto& w : workloads) {
      if (!w.technique.empty() && w.technique != t->name) continue;
      const int plain = int(runs.size());  // this workload's plain run, every variant's base
      for (size_t vi = 0; vi <= variants.size(); ++vi) {
        TechniqueRun r;
        r.technique = t;
        r.workload = w;
        r.name = t->name;
        Settings s;
        s = apply_preset(*t, o.preset, s);  // the reference: 1 sample per pixel per frame (its default)
        if (vi > 0) {
          const auto& [label, opts] = variants[vi - 1];
          // A variant naming an option the technique does not have (the reference has no
          // direct_light) is not run for it; a bad value of an option it has is an error.
          std::vector<std::string> missing;
          for (const auto& [name, value] : opts)
            if (std::none_of(technique_options(*t).begin(), technique_options(*t).end(),
                             [&](const TechniqueOption& to) { return to.name == name; }))
              missing.push_back(name);
          if (!missing.empty()) {
            if (skipped_variants.insert(label + "/" + t->name).second)
              fmt::print("--variant {}: not run for {} (it has no option {})\n", label, t->name,
                         fmt::join(missing, ", "));
            continue;
          }
          try {
            s = apply_options(*t, s, opts);
          } catch (const std::invalid_argument& e) {
            throw PerfError(fmt::format("--variant {}: {}: {}", label, t->name, e.what()));
          }
          r.name = t->name + "+" + label;
          r.base = plain;
          r.variant_options = opts;
        }
        r.settings_full = s;
        r.settings_full.width = w.width;
        r.settings_full.height = w.height;
        r.settings_run = s;
        r.settings_run.width = w.run_width;
        r.settings_run.height = w.run_height;
        r.outputs = outs;
        r.plan_full = compile_for(*t, scene, r.settings_full, outs.resources);
        // Passes that run only because an AOV other than radiance is planned: the frame total
        // includes them (and says how much they are).
        const Plan radiance_only = compile_for(*t, scene, r.settings_full, {t->output});
        for (const PlannedPass* pp : r.plan_full.running())
          if (std::none_of(radiance_only.passes.begin(), radiance_only.passes.end(),
                           [&](const PlannedPass& q) { return q.name == pp->name && q.runs; }))
            r.aov_only.insert(pp->name);
        runs.push_back(std::move(r));
      }
    }
  }
  auto t_start = std::chrono::steady_clock::now();
  for (uint32_t rep = 0; rep < repeats; ++rep)
    for (auto& r : runs) {
      Executor ex(*gpu, scene, r.settings_run, make_passes(*r.technique), r.outputs.resources);
      if (rep == 0) {
        r.plan_run = ex.plan();
        for (auto* pp : r.plan_run.running()) {
          PassRun pr;
          pr.name = pp->name;
          pr.raster = pp->kind == PassKind::graphics;
          pr.traces_rays = pp->traces_rays;
          // Work at the profile's workload: from the plan compiled at that size. (Bytes, which
          // need the measured counters, are counted after the repeats.)
          const PlannedPass* full = pp;
          for (auto* fp : r.plan_full.running())
            if (fp->name == pp->name) full = fp;
          pr.counters = work_counters(*full, r.settings_full);
          // The scale to the workload when the pass moves no plan bytes: the pixel ratio.
          pr.work_scale = double(r.workload.width) * r.workload.height / (double(r.workload.run_width) * r.workload.run_height);
          r.passes.push_back(std::move(pr));
        }
      }
      // The timing every command shares (frame_timing.h): scan off, warm-up, timed frames.
      const FrameTiming timed = time_frames(ex, warmup, frames);
      // Work the GPU counted (PassDecl::measured): read back after the timed frames, so the
      // readback is in no timed frame; the last frame's value, averaged over the repeats. Each
      // buffer is read once (several counters, and passes, share rc_counters).
      std::map<std::string, std::vector<uint8_t>> readbacks;
      for (auto* pp : ex.plan().running())
        for (const MeasuredCounter& m : pp->measured)
          for (auto& pr : r.passes)
            if (pr.name == pp->name) {
              auto it = readbacks.find(m.resource);
              if (it == readbacks.end()) it = readbacks.emplace(m.resource, ex.read_buffer(m.resource)).first;
              const std::vector<uint8_t>& raw = it->second;
              uint32_t v = 0;
              if (m.offset + sizeof(v) <= raw.size()) std::memcpy(&v, raw.data() + m.offset, sizeof(v));
              const double prev = pr.counters.contains(m.name) ? pr.counters[m.name].get<double>() : 0.0;
              pr.counters[m.name] = prev + double(v) / repeats;
            }
      // Dispatch profile: frames apart from the timed ones (a timestamp after every dispatch
      // may serialise work), for how each pass's time splits over its dispatches and their threads.
      ex.enable_dispatch_profile(true);
      for (uint32_t f = 0; f < profile_frames; ++f) {
        const FrameResult fr = ex.run_frame();
        for (auto& pt : fr.passes)
          for (auto& pr : r.passes)
            if (pr.name == pt.name) {
              add_dispatch_samples(pr.dispatches, pt.dispatches);
              std::vector<const Pipeline*> ran;
              for (const DispatchTiming& d : pt.dispatches) ran.push_back(d.pipeline);
              add_pipelines(pr.pipelines, ran);
            }
      }
      ex.enable_dispatch_profile(false);
      for (const FrameResult& fr : timed.frames) {
        for (auto& pt : fr.passes)
          for (auto& pr : r.passes)
            if (pr.name == pt.name) {
              pr.samples.push_back(pt.ms);
              pr.repeat.push_back(rep);
            }
        r.frame_ms.push_back(fr.total_ms);
        r.frame_repeat.push_back(rep);
      }
      fmt::print("  [{}/{}] {} @ {} ({}): frame median {:.3f} ms\n", rep + 1, repeats, r.name,
                 r.workload.name(), r.workload.run_name(), median_of(r.frame_ms));
      std::fflush(stdout);
    }
  const double run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  // Bytes per pass, at the run's size and the profile's: sparse slots (Slot::touched) count the
  // bytes their GPU-counted work moves, known only now: the run's measured counters by name
  // (PassDecl::measured; declared work is not used, its names repeat across passes).
  for (auto& r : runs) {
    std::map<std::string, double> measured;
    for (auto* pp : r.plan_run.running())
      for (const MeasuredCounter& m : pp->measured)
        for (auto& pr : r.passes)
          if (pr.name == pp->name && pr.counters.contains(m.name)) measured[m.name] = pr.counters[m.name].get<double>();
    for (auto& pr : r.passes) {
      const PlannedPass *run_pass = nullptr, *full_pass = nullptr;
      for (auto* pp : r.plan_run.running())
        if (pp->name == pr.name) run_pass = pp;
      for (auto* pp : r.plan_full.running())
        if (pp->name == pr.name) full_pass = pp;
      if (!run_pass) continue;
      if (!full_pass) full_pass = run_pass;
      pr.bytes_run = pass_bytes(r.plan_run, *run_pass, &measured);
      pr.bytes_full = pass_bytes(full_pass == run_pass ? r.plan_run : r.plan_full, *full_pass, &measured);
      if (pr.bytes_run.total()) pr.work_scale = double(pr.bytes_full.total()) / double(pr.bytes_run.total());
    }
  }

  nlohmann::json out;
  out["format"] = "gibench-perf-1";
  out["revision"] = GIB_REVISION;
  out["date"] = utc_now();
  out["device"] = {{"name", dev.name}, {"type", dev.type}, {"driver", dev.driver_name},
                   {"driver_info", dev.driver_info}, {"api_version", dev.api_version},
                   {"subgroup_size", dev.subgroup_size}, {"compute_units", dev.compute_units},
                   {"resident_threads", dev.resident_threads}, {"residency_source", dev.residency_source}};
  out["occupancy_term"] = occupancy_off.empty() ? nlohmann::json({{"on", true}, {"profiled_frames", profile_frames}})
                                                : nlohmann::json({{"on", false}, {"why", occupancy_off}});
  out["calibration"] = cal.to_json();
  out["settings"] = {{"case", o.case_name}, {"scene", scene_path}, {"preset", o.preset}, {"frames", frames},
                     {"warmup", warmup}, {"repeats", repeats}, {"scale_resolution", scale},
                     {"timing", cpu ? "host clock per pass" : "timestamps"}, {"profiles", o.profiles},
                     {"data", {{"profiles", profiles_path}, {"seeds", seeds_path}}}, {"seconds", run_seconds}};
  auto& jruns = out["runs"] = nlohmann::json::array();
  auto& jnoise = out["noise_floor"] = nlohmann::json::object();
  auto& jseed = out["seed_comparison"] = nlohmann::json::array();
  nlohmann::json medians = nlohmann::json::object();

  std::vector<double> detectables;
  std::string worst_key;
  double worst = 0;
  bool raster_explained = false;  // the fill-rate scaling is explained at the first raster pass
  bool walk_explained = false;    // and the software BVH walk at the first tracing pass

  for (auto& r : runs) {
    const Workload& w = r.workload;
    fmt::print("\n== {} @ {} (profiles: ", r.name, w.name());
    for (size_t i = 0; i < w.profiles.size(); ++i) fmt::print("{}{}", i ? ", " : "", w.profiles[i]->name);
    fmt::print(")");
    if (scale != 1) fmt::print(" measured at {} (scale {}), pass times scaled to {} by work x", w.run_name(), scale_text(scale), w.name());
    if (!w.seed_table.empty()) fmt::print(" [{}'s workload, not the profile's target]", w.seed_table);
    fmt::print(" ==\n");
    fmt::print("planned AOVs: {}", fmt::join(r.outputs.aovs, ", "));
    if (!r.outputs.left_out.empty()) fmt::print("; left out: {}", fmt::join(r.outputs.left_out, ", "));
    fmt::print("\n");
    nlohmann::json jculled = nlohmann::json::array();
    for (const PlannedPass& pp : r.plan_run.passes)
      if (!pp.runs) {
        fmt::print("culled {}: {}\n", pp.name, pp.reason);
        jculled.push_back({{"pass", pp.name}, {"reason", pp.reason}});
      }
    if (!r.aov_only.empty())
      fmt::print("AOV-only passes (feed no radiance, marked *): {}\n",
                 fmt::join(std::vector<std::string>(r.aov_only.begin(), r.aov_only.end()), ", "));
    bool has_probe_pass = false;
    for (auto& pr : r.passes) has_probe_pass |= pr.name.find("probe") != std::string::npos;
    // A technique with a per-frame probe budget (probe-volume's probe_budget) ran at its preset's
    // or variant's; one without (radiance-cache) at its own schedule.
    std::optional<double> budget;
    for (const TechniqueOption& opt : technique_options(*r.technique))
      if (opt.name == "probe_budget" && opt.read) budget = opt.read(r.settings_full);
    for (auto* p : w.profiles)
      if (p->probes_per_frame && has_probe_pass) {
        if (!budget)
          fmt::print("note: {} targets {} probes/frame; {} has no probes-per-frame setting, so it ran at its own "
                     "(16^3 probes of one cascade per frame)\n",
                     p->name, *p->probes_per_frame, r.name);
        else if (*budget != double(*p->probes_per_frame))
          fmt::print("note: {} targets {} probes/frame; {} ran with probe_budget {} (set it with --variant to match)\n",
                     p->name, *p->probes_per_frame, r.name, *budget);
      }
    std::string header = fmt::format("{:<26} {:>10} {:>21} {:>7} {:>10} {:>9} {:>9} {:>9} |", "pass", "meas ms",
                                     "IQR [q1, q3]", "work x", "ms @full", "MB moved", "mem ms", "comp ms");
    for (auto* p : w.profiles) header += fmt::format(" {:>13}", p->name);
    fmt::print("{}\n", header);

    nlohmann::json jr{{"technique", r.name},
                      {"workload", {{"width", w.width}, {"height", w.height}}},
                      {"run", {{"width", w.run_width}, {"height", w.run_height}}},
                      {"profiles", nlohmann::json::array()},
                      {"aovs", r.outputs.aovs},
                      {"outputs", r.outputs.resources},
                      {"aovs_left_out", r.outputs.left_out},
                      {"culled", jculled},
                      {"aov_only_passes", std::vector<std::string>(r.aov_only.begin(), r.aov_only.end())},
                      {"seed_table_workload", w.seed_table}};
    for (auto* p : w.profiles) jr["profiles"].push_back(p->name);
    std::map<std::string, double> scaled_total, aov_only_scaled;
    double aov_only_meas = 0;
    double meas_total = 0, full_total = 0, bytes_total = 0, mem_total = 0, comp_total = 0;
    CostByPass scaled_by_pass;  // profile -> pass -> ms
    CostByPass flop_by_pass;    // the same without the occupancy term
    CostByPass nolat_by_pass;   // the same with the occupancy term but no dispatch latency
    std::map<std::string, std::vector<std::pair<std::string, double>>> pass_order;  // the same, in run order
    for (auto& pr : r.passes) {
      Summary s = summarize_samples(pr.samples);
      double full_ms = s.median * pr.work_scale;
      PassSplit split = split_pass(full_ms, double(pr.bytes_full.total()), thr);
      const bool aov_only = r.aov_only.count(pr.name) > 0;
      if (aov_only) aov_only_meas += s.median;
      std::string line = fmt::format("{:<26} {:>10} {:>21} {:>7.2f} {:>10} {:>9.2f} {:>9} {:>9} |", pr.name + (aov_only ? " *" : ""),
                                     fmt_ms(s.median), fmt::format("[{}, {}]", fmt_ms(s.q1), fmt_ms(s.q3)),
                                     pr.work_scale, fmt_ms(full_ms), pr.bytes_full.total() / 1e6,
                                     fmt_ms(split.memory_ms), fmt_ms(split.compute_ms));
      nlohmann::json scaled = nlohmann::json::object(), scaled_flop = nlohmann::json::object();
      std::vector<std::string> raster_fallback;
      // The occupancy term: the pass's compute time shared over its dispatches (profiled frames).
      std::string occ_why = occupancy_off;
      std::vector<DispatchShare> shares;
      if (occ_why.empty() && !pr.raster) shares = dispatch_shares(pr.dispatches, occ_why);
      nlohmann::json jocc{{"dispatches", nlohmann::json::array()}, {"factor", nlohmann::json::object()}};
      for (const DispatchShare& d : shares) jocc["dispatches"].push_back({{"fraction", d.fraction}, {"threads", d.threads}});
      if (pr.raster) occ_why = "a rasterising pass (fill-rate scaling)";
      if (!occ_why.empty()) jocc["off"] = occ_why;
      std::string occ_line;
      for (auto* p : w.profiles) {
        std::optional<double> raster = pr.raster ? scale_raster_to_profile(full_ms, thr, *p) : std::nullopt;
        if (pr.raster && !raster) raster_fallback.push_back(p->name);
        double occ = 1, occ_nolat = 1;
        if (!shares.empty() && p->resident_threads) {
          occ = pass_occupancy_factor(shares, double(thr.resident_threads), double(p->resident_threads),
                                      cal.dispatch_latency_ms, full_ms);
          occ_nolat = pass_occupancy_factor(shares, double(thr.resident_threads), double(p->resident_threads));
        }
        if (!shares.empty()) {
          jocc["factor"][p->name] = occ;
          jocc["factor_no_dispatch_latency"][p->name] = occ_nolat;
        }
        if (std::fabs(occ - 1) > 0.005) occ_line += fmt::format(" x{:.3f} @ {}", occ, p->name);
        const bool by_fill = raster.has_value();
        const double fill_ms = raster.value_or(0.0);
        const double ms = by_fill ? fill_ms : scale_to_profile(split, thr, *p, occ);
        const double flop_ms = by_fill ? fill_ms : scale_to_profile(split, thr, *p);
        nolat_by_pass[p->name][pr.name] += by_fill ? fill_ms : scale_to_profile(split, thr, *p, occ_nolat);
        scaled_flop[p->name] = flop_ms;
        scaled[p->name] = ms;
        scaled_total[p->name] += ms;
        if (aov_only) aov_only_scaled[p->name] += ms;
        line += fmt::format(" {:>13}", fmt_ms(ms));
        scaled_by_pass[p->name][pr.name] += ms;
        flop_by_pass[p->name][pr.name] += flop_ms;
        pass_order[p->name].push_back({pr.name, ms});
      }
      fmt::print("{}\n", line);
      if (!occ_line.empty()) {
        // The dispatches that carry most of the pass's time, with their threads.
        std::vector<DispatchShare> top = shares;
        std::sort(top.begin(), top.end(), [](auto& a, auto& b) { return a.fraction > b.fraction; });
        std::string parts;
        for (size_t k = 0; k < std::min<size_t>(3, top.size()); ++k)
          parts += fmt::format("{}{:.0f} threads {:.0f}%", k ? ", " : "", top[k].threads, top[k].fraction * 100);
        fmt::print("  occupancy:{} on the FLOP ratio ({} dispatches; {}{})\n", occ_line, shares.size(), parts,
                   top.size() > 3 ? ", ..." : "");
      }
      if (pr.traces_rays && !walk_explained)
        fmt::print("  {} walks the BVH in its shaders (no ray queries here): scaled as arithmetic by the FLOP split, "
                   "where a console with RT hardware walks it in fixed-function units\n", pr.name);
      else if (pr.traces_rays)
        fmt::print("  {} walks the BVH in its shaders (as above)\n", pr.name);
      walk_explained |= pr.traces_rays;
      if (const std::string stats = pipeline_statistics_line(pr.pipelines); !stats.empty())
        fmt::print("  pipelines: {}\n", stats);
      if (pr.raster) {
        if (!raster_explained)
          fmt::print("  {} rasterises: scaled by fill rate (this device {:.2f} Gpixel/s calibrated; a profile's ROPs x "
                     "clock), not by the FLOP split, as every rasterising pass below. A GPU with few graphics-capable "
                     "units (an H100) rasterises far below its compute rate, so its raster time says little about a "
                     "console's.\n",
                     pr.name, thr.fill_gpix);
        else
          fmt::print("  {} rasterises: scaled by fill rate\n", pr.name);
        raster_explained = true;
        if (!raster_fallback.empty())
          fmt::print("  {}: no fill rate for {} (no ROP count in the profile, or no raster calibration): scaled like "
                     "compute there\n", pr.name, fmt::join(raster_fallback, ", "));
      }
      meas_total += s.median;
      full_total += full_ms;
      bytes_total += double(pr.bytes_full.total());
      mem_total += split.memory_ms;
      comp_total += split.compute_ms;
      const std::string key = fmt::format("{}/{}/{}", r.name, pr.name, w.run_name());
      medians[key] = s.median;

      // Noise floor: the same configuration timed twice in this run (even vs odd repeats, or
      // the two halves of the frames when there is one repeat).
      std::vector<double> a, b;
      for (size_t i = 0; i < pr.samples.size(); ++i) {
        bool first = repeats >= 2 ? pr.repeat[i] % 2 == 0 : i < pr.samples.size() / 2;
        (first ? a : b).push_back(pr.samples[i]);
      }
      nlohmann::json jn;
      double det = detectable_regression(pr.samples);
      jn["detectable_regression"] = std::isfinite(det) ? nlohmann::json(det) : nlohmann::json(nullptr);
      if (a.size() && b.size()) {
        bool positive = true;
        for (double v : pr.samples) positive &= v > 0;
        if (positive) {
          RankTest t = mann_whitney(a, b);
          jn.update({{"a_vs_b_change", t.change}, {"ci", {t.ci_low, t.ci_high}}, {"p", t.p},
                     {"verdict", verdict_name(judge(t, o.min_change))}, {"n_a", a.size()}, {"n_b", b.size()}});
        }
      }
      jnoise[key] = jn;
      if (std::isfinite(det)) {
        detectables.push_back(det);
        if (det > worst) worst = det, worst_key = key;
      }

      jr["passes"].push_back({{"name", pr.name},
                              {"key", key},
                              {"samples_ms", pr.samples},
                              {"sample_repeat", pr.repeat},
                              {"median_ms", s.median},
                              {"q1_ms", s.q1},
                              {"q3_ms", s.q3},
                              {"min_ms", s.min},
                              {"max_ms", s.max},
                              {"bytes_read", pr.bytes_run.read},
                              {"bytes_written", pr.bytes_run.written},
                              {"bytes_read_full", pr.bytes_full.read},
                              {"sparse_slots", pr.bytes_full.sparse},
                              {"sparse_slots_unresolved", pr.bytes_full.unresolved},
                              {"bytes_written_full", pr.bytes_full.written},
                              {"work_scale", pr.work_scale},
                              {"device_ms_full", full_ms},
                              {"memory_ms", split.memory_ms},
                              {"compute_ms", split.compute_ms},
                              {"scaling", pr.raster ? "fill_rate" : "flop_bandwidth_split"},
                              {"traces_rays", pr.traces_rays},
                              {"aov_only", aov_only},
                              {"scaled_ms", scaled},
                              {"scaled_ms_flop_split", scaled_flop},
                              {"occupancy", jocc},
                              {"pipelines", pipeline_statistics_json(pr.pipelines)},
                              {"counters", pr.counters}});
    }
    std::string line = fmt::format("{:<26} {:>10} {:>21} {:>7} {:>10} {:>9.2f} {:>9} {:>9} |", "frame (sum of passes)",
                                   fmt_ms(meas_total), "", "", fmt_ms(full_total), bytes_total / 1e6, fmt_ms(mem_total),
                                   fmt_ms(comp_total));
    for (auto* p : w.profiles) line += fmt::format(" {:>13}", fmt_ms(scaled_total[p->name]));
    fmt::print("{}\n", line);
    if (!r.aov_only.empty()) {
      std::string l = fmt::format("{:<26} {:>10} {:>21} {:>7} {:>10} {:>9} {:>9} {:>9} |", "  of which AOV-only (*)",
                                  fmt_ms(aov_only_meas), "", "", "", "", "", "");
      for (auto* p : w.profiles) l += fmt::format(" {:>13}", fmt_ms(aov_only_scaled[p->name]));
      fmt::print("{}\n", l);
    }
    fmt::print("the frame total includes every planned pass{}\n",
               r.aov_only.empty() ? " (none of them feeds only an AOV other than radiance)"
                                  : ", AOV-only passes (*) too: subtract their line for the radiance frame");
    Summary fs = summarize_samples(r.frame_ms);
    fmt::print("frame measured end to end: median {} ms, IQR [{}, {}] at {}\n", fmt_ms(fs.median), fmt_ms(fs.q1),
               fmt_ms(fs.q3), w.run_name());
    for (auto* pp : r.plan_run.running()) {
      if (pp->measured.empty()) continue;
      for (auto& pr : r.passes)
        if (pr.name == pp->name) {
          std::vector<std::string> parts;
          for (const MeasuredCounter& m : pp->measured)
            if (pr.counters.contains(m.name)) parts.push_back(fmt::format("{} {:g}", m.name, pr.counters[m.name].get<double>()));
          fmt::print("measured work (GPU counters after the timed frames, at {}): {}: {}\n", w.run_name(), pr.name,
                     fmt::join(parts, ", "));
        }
    }
    for (auto& pr : r.passes) {
      if (!pr.bytes_full.sparse.empty())
        fmt::print("sparse access (bytes moved, not the buffer's size): {}: {}\n", pr.name, fmt::join(pr.bytes_full.sparse, "; "));
      if (!pr.bytes_full.unresolved.empty())
        fmt::print("sparse access counted at the buffer's size (its counter was not measured): {}: {}\n", pr.name,
                   fmt::join(pr.bytes_full.unresolved, ", "));
    }
    const std::string fkey = fmt::format("{}/frame/{}", r.name, w.run_name());
    medians[fkey] = fs.median;
    jr["frame"] = {{"key", fkey}, {"samples_ms", r.frame_ms}, {"sample_repeat", r.frame_repeat},
                   {"median_ms", fs.median}, {"sum_of_pass_medians_ms", meas_total},
                   {"device_ms_full", full_total}, {"scaled_ms", scaled_total},
                   {"includes_aov_only_passes", !r.aov_only.empty()},
                   {"aov_only_sum_of_pass_medians_ms", aov_only_meas}, {"aov_only_scaled_ms", aov_only_scaled}};
    // The budget tree per profile: categories with the seed's budgets where the profile has them
    // (GoW Ragnarok: PS4), without ("-") elsewhere, so every profile's frame reads by category.
    for (auto* p : w.profiles) {
      if (!budgets || !w.seed_table.empty()) continue;
      BudgetTree tree = budget_tree(*budgets, p->name, pass_order[p->name]);
      fmt::print("\n-- {} budgets @ {} (console-scaled) --\n{}", r.name, p->name, format_budget_tree(tree));
      jr["budgets"].push_back(to_json(tree));
      budget_trees.push_back({fmt::format("{} @ {} ({})", r.name, p->name, w.name()), std::move(tree)});
    }
    jruns.push_back(jr);

    for (const SeedTable& table : seeds)
      if (table.technique == r.technique->name) add_seed_rows(table, r, scaled_by_pass, flop_by_pass, nolat_by_pass, jseed);
  }
  print_seed_comparison(seeds, techs, jseed);
  if (!o.budget_html.empty()) {
    std::ofstream html(o.budget_html);
    if (!html) throw PerfError(fmt::format("--budget-html {}: cannot write", o.budget_html));
    html << budget_html(budget_trees);
    fmt::print("wrote {} ({} budget trees)\n", o.budget_html, budget_trees.size());
  }

  fmt::print("\n== noise floor: the same configuration timed twice in this run ({}) ==\n",
             repeats >= 2 ? "even vs odd repeats" : "first vs second half of the frames");
  fmt::print("{:<44} {:>9} {:>21} {:>8} {:>12}  {}\n", "benchmark", "A vs B", "95% CI", "p", "detectable", "A vs B");
  for (auto& [key, jn] : jnoise.items()) {
    if (!jn.contains("a_vs_b_change")) continue;
    double det = jn["detectable_regression"].is_null() ? INFINITY : jn["detectable_regression"].get<double>();
    // Here a significant difference does not mean a regression: the code is the same, so it
    // says the machine drifted between the two halves (clocks, other load).
    std::string v = jn["verdict"].get<std::string>();
    std::string what = v == "unchanged" ? "halves agree" : v == "too few samples" ? v : "halves differ (drift)";
    fmt::print("{:<44} {:>9} {:>21} {:>8.3f} {:>12}  {}\n", key, fmt_pct(jn["a_vs_b_change"]),
               fmt::format("[{}, {}]", fmt_pct(jn["ci"][0]), fmt_pct(jn["ci"][1])), jn["p"].get<double>(),
               fmt_pct(det), what);
  }
  if (!detectables.empty()) {
    fmt::print("smallest regression detectable at 95% confidence (rank test, {} samples per side): median over passes "
               "{}, worst {} ({}); perf-diff also needs a change of at least {:.0f}% to flag it\n",
               frames * repeats, fmt_pct(median_of(detectables)), fmt_pct(worst), worst_key, o.min_change * 100);
    out["noise_summary"] = {{"median_detectable", median_of(detectables)}, {"worst_detectable", worst},
                            {"worst_key", worst_key}, {"min_change", o.min_change}};
  }

  // Variants against their plain run: the same repeats, interleaved, so machine drift hits both.
  auto& jvar = out["variants"] = nlohmann::json::array();
  for (auto& r : runs) {
    if (r.base < 0) continue;
    const TechniqueRun& b = runs[size_t(r.base)];
    fmt::print("\n== variant {} vs {} @ {} (measured side by side; change = variant / plain - 1, Hodges-Lehmann "
               "with 95% CI) ==\n",
               r.name, b.name, r.workload.run_name());
    fmt::print("{:<26} {:>10} {:>10} {:>9} {:>21} {:>8}  {}\n", "pass", "plain ms", "variant ms", "change", "95% CI",
               "p", "verdict");
    auto row = [&](const std::string& pass, const std::vector<double>& base, const std::vector<double>& next) {
      if (base.empty() || next.empty()) {
        fmt::print("{:<26} {:>10} {:>10}  {}\n", pass, base.empty() ? "-" : fmt_ms(median_of(base)),
                   next.empty() ? "-" : fmt_ms(median_of(next)), base.empty() ? "only in the variant" : "culled in the variant");
        jvar.push_back({{"variant", r.name}, {"base", b.name}, {"pass", pass}});
        return;
      }
      RankTest t = mann_whitney(base, next);
      Verdict v = judge(t, o.min_change);
      fmt::print("{:<26} {:>10} {:>10} {:>9} {:>21} {:>8.3f}  {}\n", pass, fmt_ms(median_of(base)),
                 fmt_ms(median_of(next)), fmt_pct(t.change),
                 t.ci_valid ? fmt::format("[{}, {}]", fmt_pct(t.ci_low), fmt_pct(t.ci_high)) : "-", t.p,
                 verdict_name(v));
      jvar.push_back({{"variant", r.name}, {"base", b.name}, {"pass", pass}, {"base_median_ms", median_of(base)},
                      {"variant_median_ms", median_of(next)}, {"change", t.change}, {"ci", {t.ci_low, t.ci_high}},
                      {"p", t.p}, {"verdict", verdict_name(v)}});
    };
    std::set<std::string> done;
    for (auto& bp : b.passes) {
      auto it = std::find_if(r.passes.begin(), r.passes.end(), [&](const PassRun& x) { return x.name == bp.name; });
      row(bp.name, bp.samples, it == r.passes.end() ? std::vector<double>{} : it->samples);
      done.insert(bp.name);
    }
    for (auto& vp : r.passes)
      if (!done.count(vp.name)) row(vp.name, {}, vp.samples);
    row("frame", b.frame_ms, r.frame_ms);
  }

  out["seed_alpha_comparison"] = alpha_cost_comparison(runs, alpha_costs);

  if (!o.json.empty()) {
    std::ofstream(o.json) << out.dump(1) << "\n";
    fmt::print("wrote {}\n", o.json);
  }
  if (!o.no_history) {
    nlohmann::json line{{"date", out["date"]},
                        {"revision", GIB_REVISION},
                        {"device", dev.name},
                        {"driver", dev.driver_name + " " + dev.driver_info},
                        {"case", o.case_name},
                        {"preset", o.preset},
                        {"scale_resolution", scale},
                        {"fp32_gflops", thr.fp32_gflops},
                        {"bandwidth_gbs", thr.bandwidth_gbs},
                        {"fill_gpix", thr.fill_gpix},
                        {"median_ms", medians}};
    std::ofstream h(hist, std::ios::app);
    if (!h) throw PerfError(fmt::format("--history {}: cannot append", hist));
    h << line.dump() << "\n";
    fmt::print("appended a line to {}\n", hist);
  }
  return 0;
}

BenchVariant parse_variant(const std::string& v) {
  auto colon = v.find(':');
  if (colon == std::string::npos || colon == 0)
    throw PerfError(fmt::format("--variant \"{}\": expected LABEL:NAME=VALUE[,NAME=VALUE...]", v));
  BenchVariant out{v.substr(0, colon), {}};
  std::string rest = v.substr(colon + 1);
  for (size_t at = 0; at <= rest.size();) {
    size_t end = rest.find(',', at);
    if (end == std::string::npos) end = rest.size();
    std::string kv = rest.substr(at, end - at);
    auto eq = kv.find('=');
    char* stop = nullptr;
    double value = eq == std::string::npos ? 0 : std::strtod(kv.c_str() + eq + 1, &stop);
    if (eq == std::string::npos || eq == 0 || stop == kv.c_str() + eq + 1 || *stop != '\0')
      throw PerfError(fmt::format("--variant \"{}\": expected NAME=VALUE, got \"{}\"", v, kv));
    out.options[kv.substr(0, eq)] = value;
    at = end + 1;
  }
  return out;
}

// ---------------------------------------------------------------- perf-diff
SampleFile parse_sample_file(const std::string& raw, const std::string& file) {
  // Google Benchmark writes NaN / inf for undefined aggregates (the cv of a zero counter): not
  // JSON, so they become null before parsing.
  static const std::regex non_finite(R"((:\s*)-?(nan|NaN|inf|Inf|Infinity)\b)");
  const std::string text = std::regex_replace(raw, non_finite, "$1null");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw PerfError(fmt::format("{}: expected valid JSON, got a parse error: {}", file, e.what()));
  }
  SampleFile sf;
  auto need_samples = [&](const nlohmann::json& v, const std::string& ptr) {
    if (!v.is_array() || v.empty())
      throw PerfError(fmt::format("{}: {}: expected a non-empty array of ms, got {}", file, ptr, v.type_name()));
    std::vector<double> out;
    for (auto& x : v) {
      if (!x.is_number() || !(x.get<double>() > 0))
        throw PerfError(fmt::format("{}: {}: expected positive numbers (ms), got {}", file, ptr, x.dump()));
      out.push_back(x.get<double>());
    }
    return out;
  };
  if (j.is_object() && j.value("format", "") == "gibench-perf-1") {
    sf.format = "gibench-perf-1";
    if (j.contains("device") && j["device"].is_object()) sf.device = j["device"].value("name", "");
    if (!j.contains("runs") || !j["runs"].is_array())
      throw PerfError(fmt::format("{}: /runs: expected an array, got {}", file, j.contains("runs") ? j["runs"].type_name() : "nothing"));
    for (size_t i = 0; i < j["runs"].size(); ++i) {
      auto& r = j["runs"][i];
      std::string ptr = fmt::format("/runs/{}", i);
      if (!r.contains("passes") || !r["passes"].is_array())
        throw PerfError(fmt::format("{}: {}/passes: expected an array", file, ptr));
      for (size_t k = 0; k < r["passes"].size(); ++k) {
        auto& p = r["passes"][k];
        std::string pp = fmt::format("{}/passes/{}", ptr, k);
        if (!p.contains("key") || !p["key"].is_string())
          throw PerfError(fmt::format("{}: {}/key: expected a string", file, pp));
        sf.samples[p["key"]] = need_samples(p.value("samples_ms", nlohmann::json()), pp + "/samples_ms");
      }
      if (r.contains("frame") && r["frame"].contains("key"))
        sf.samples[r["frame"]["key"]] = need_samples(r["frame"]["samples_ms"], ptr + "/frame/samples_ms");
    }
    if (j.contains("noise_floor") && j["noise_floor"].is_object())
      for (auto& [k, v] : j["noise_floor"].items())
        if (v.is_object() && v.contains("detectable_regression") && v["detectable_regression"].is_number())
          sf.detectable[k] = v["detectable_regression"].get<double>();
    return sf;
  }
  if (j.is_object() && j.contains("benchmarks") && j["benchmarks"].is_array()) {
    sf.format = "google-benchmark";
    if (j.contains("context") && j["context"].is_object()) sf.device = j["context"].value("gpu_device", "");
    for (size_t i = 0; i < j["benchmarks"].size(); ++i) {
      auto& b = j["benchmarks"][i];
      if (b.value("run_type", "iteration") != "iteration") continue;
      std::string ptr = fmt::format("/benchmarks/{}", i);
      std::string name = b.value("run_name", b.value("name", ""));
      if (name.empty()) throw PerfError(fmt::format("{}: {}/run_name: expected a string", file, ptr));
      if (!b.contains("real_time") || !b["real_time"].is_number())
        throw PerfError(fmt::format("{}: {}/real_time: expected a number", file, ptr));
      std::string unit = b.value("time_unit", "ns");
      double to_ms = unit == "ns" ? 1e-6 : unit == "us" ? 1e-3 : unit == "ms" ? 1.0 : unit == "s" ? 1e3 : -1;
      if (to_ms < 0) throw PerfError(fmt::format("{}: {}/time_unit: expected ns|us|ms|s, got '{}'", file, ptr, unit));
      double v = b["real_time"].get<double>() * to_ms;
      if (v > 0) sf.samples[name].push_back(v);
    }
    return sf;
  }
  throw PerfError(fmt::format("{}: expected a `gibench bench --json` file (format gibench-perf-1) or Google Benchmark "
                              "JSON (benchmarks[]), got neither",
                              file));
}

SampleFile load_sample_file(const std::string& path) { return parse_sample_file(read_file(path), path); }

int cmd_perf_diff(const DiffOptions& o) {
  SampleFile base = load_sample_file(o.base), next = load_sample_file(o.next);
  if (!base.device.empty() && !next.device.empty() && base.device != next.device)
    fmt::print("warning: different devices: {} vs {}; timings are not comparable\n", base.device, next.device);
  fmt::print("perf-diff {} -> {}\nMann-Whitney U (two-sided, {:.0f}%), change = Hodges-Lehmann estimate of new/base - 1 "
             "with its {:.0f}% interval; a regression needs the interval above 0 and a change >= {:.0f}%\n",
             o.base, o.next, o.confidence * 100, o.confidence * 100, o.min_change * 100);
  fmt::print("{:<44} {:>10} {:>10} {:>9} {:>21} {:>8} {:>10}  {}\n", "benchmark", "base ms", "new ms", "change",
             fmt::format("{:.0f}% CI", o.confidence * 100), "p", "base floor", "verdict");
  int regressions = 0;
  std::set<std::string> keys;
  for (auto& [k, v] : base.samples) keys.insert(k);
  for (auto& [k, v] : next.samples) keys.insert(k);
  for (auto& k : keys) {
    auto b = base.samples.find(k), n = next.samples.find(k);
    if (b == base.samples.end() || n == next.samples.end()) {
      fmt::print("{:<44} only in {}\n", k, b == base.samples.end() ? "new" : "base");
      continue;
    }
    RankTest t = mann_whitney(b->second, n->second, o.confidence);
    Verdict v = judge(t, o.min_change);
    if (v == Verdict::regression) ++regressions;
    auto fl = base.detectable.find(k);
    fmt::print("{:<44} {:>10} {:>10} {:>9} {:>21} {:>8.4f} {:>10}  {}\n", k, fmt_ms(median_of(b->second)),
               fmt_ms(median_of(n->second)), fmt_pct(t.change),
               t.ci_valid ? fmt::format("[{}, {}]", fmt_pct(t.ci_low), fmt_pct(t.ci_high)) : std::string("-"), t.p,
               fl != base.detectable.end() ? fmt_pct(fl->second) : std::string("-"), verdict_name(v));
  }
  fmt::print("{} regression{}\n", regressions, regressions == 1 ? "" : "s");
  return regressions ? 1 : 0;
}

}  // namespace gib::perf
