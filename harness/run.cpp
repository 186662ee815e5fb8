// `gibench run`, the pipeline:
//   1. plan (plan.h): every row of the selected cases; the profile, --technique and --shard pick
//      the rows this run renders, the rest of the profile's plan is listed as not run;
//   2. render + evaluate (row_runner.h -> evaluate.h -> measure.h), in this process or in worker
//      processes (jobs.h), with live progress (progress.h);
//   3. verdict (verdict.h), per row as it finishes;
//   4. report (report.h): results.json, junit.xml, index.html, the table and the summary.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fnmatch.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <set>

#include "harness/attribution/suite_attribution.h"
#include "harness/case_render.h"
#include "harness/jobs.h"
#include "harness/plan.h"
#include "harness/progress.h"
#include "harness/report.h"
#include "harness/row_runner.h"
#include "harness/shard.h"
#include "harness/suite.h"
#include "harness/verdict.h"
#include "renderer/techniques/technique.h"
#include "renderer/vk/gpu.h"

namespace gib {

int SuiteResult::failures() const {
  int n = static_cast<int>(case_errors.size());
  for (auto& r : rows)
    n += r.status != "pass" && r.status != "known_failure" && r.status != "skipped" && r.status != "not_run";
  return n;
}

bool glob_match(const std::string& pattern, const std::string& text) {
  return fnmatch(pattern.c_str(), text.c_str(), 0) == 0;
}

bool technique_selected(const std::vector<std::string>& techniques, const std::string& technique) {
  return techniques.empty() || std::find(techniques.begin(), techniques.end(), technique) != techniques.end();
}

std::vector<Case> select_cases(const SuiteOptions& o) {
  std::vector<Case> all = load_cases(o.cases_dir);
  if (o.case_globs.empty()) return all;
  std::vector<Case> out;
  for (auto& g : o.case_globs) {
    bool any = false;
    for (auto& c : all)
      if (glob_match(g, c.name)) {
        any = true;
        if (std::none_of(out.begin(), out.end(), [&](const Case& x) { return x.name == c.name; })) out.push_back(c);
      }
    if (!any) {
      std::vector<std::string> names;
      for (auto& c : all) names.push_back(c.name);
      throw CaseError(fmt::format("--case: expected a name or glob matching one of [{}], got '{}'",
                                  fmt::join(names, ", "), g));
    }
  }
  return out;
}

SuiteSetup setup_suite(const SuiteOptions& o, const std::string& device) {
  SuiteSetup s;
  s.cases = select_cases(o);
  for (const std::string& t : o.techniques) find_technique(t);  // an unknown name is an error, not an empty run
  s.gpu = Gpu::create({device, o.validate});
  s.suite.device = s.gpu->info();
  s.suite.device_class = device_class(s.suite.device.driver_name, s.suite.device.name);
  s.suite.golden_class = o.golden_class.empty() ? s.suite.device_class : o.golden_class;
  s.tier = resolve_tier(o.tier, s.suite.device_class);
  s.suite.tier = tier_name(s.tier);
  for (Case& c : s.cases) c = at_tier(c, s.tier);
  s.cache_root = s.tier == Tier::gpu ? reference_cache_root(o.reference_cache) : "";
  return s;
}

namespace {

// The rows of this run: those of the plan with a selected technique, in this shard; each either
// run or, left out by the profile, listed with the reason.
struct RunPlan {
  std::vector<PlannedRow> all;  // the plan (selected techniques), the shard's reference order
  std::vector<PlannedRow> run;
  std::vector<std::pair<PlannedRow, std::string>> not_run;
  nlohmann::json shard;  // the shard record, null when unsharded
};

RunPlan make_run_plan(const SuiteOptions& o, const std::vector<Case>& cases, Profile profile) {
  RunPlan rp;
  for (PlannedRow& p : plan_suite(cases, load_row_seconds(o.cases_dir)))
    if (technique_selected(o.techniques, p.technique)) rp.all.push_back(std::move(p));
  const std::map<std::string, std::string> left_out =
      profile == Profile::quick ? select_quick(cases, rp.all) : std::map<std::string, std::string>{};
  // Sharding: row i of the plan runs in shard i % N.
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  std::vector<std::string> keys, ours;
  for (size_t i = 0; i < rp.all.size(); ++i) {
    const PlannedRow& p = rp.all[i];
    keys.push_back(p.key);
    if (i % shard.count != shard.index) continue;
    ours.push_back(p.key);
    if (auto it = left_out.find(p.key); it != left_out.end()) rp.not_run.push_back({p, it->second});
    else rp.run.push_back(p);
  }
  if (shard.active())
    rp.shard = {{"index", shard.index}, {"count", shard.count}, {"plan", keys}, {"rows", ours}};
  return rp;
}

// Renders the rows in this process, in plan order.
void run_serial(SuiteSetup& s, const SuiteOptions& o, const std::vector<PlannedRow>& rows, SuiteProgress& progress) {
  RowRunner runner(*s.gpu, o, s.cases, s.tier, s.cache_root, s.suite);
  for (const PlannedRow& p : rows) {
    progress.started(p.key);
    const size_t errors = s.suite.case_errors.size();
    const ResultRow* row =
        runner.run(p, [&](const std::string& what, uint32_t d, uint32_t t) { progress.frame(p.key, what, d, t); });
    if (row)
      progress.finished(row_line(p.key, *row));
    else
      progress.finished({p.key, "error", 0, "",
                         s.suite.case_errors.size() > errors ? std::vector<std::string>{s.suite.case_errors.back()}
                                                             : std::vector<std::string>{"its case failed earlier"}});
  }
  runner.finish();
}

std::string plural(size_t n, const char* what) { return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s"); }

// --dry-run: the rows in plan order, each with its expected seconds (the last run's, else the
// model's) or why it is not run, and the expected wall time.
int print_plan(const RunPlan& rp, const std::vector<std::pair<std::string, double>>& expected, unsigned jobs) {
  std::map<std::string, double> secs(expected.begin(), expected.end());
  std::map<std::string, std::string> why;
  for (auto& [p, reason] : rp.not_run) why[p.key] = reason;
  double total = 0, longest = 0;
  for (auto& p : rp.all) {
    if (auto it = secs.find(p.key); it != secs.end()) {
      fmt::print("  run      {:>7.1f} s  {}\n", it->second, p.key);
      total += it->second;
      longest = std::max(longest, it->second);
    } else if (auto w = why.find(p.key); w != why.end()) {
      fmt::print("  not run  {:>7.1f} s  {}: {}\n", p.cost, p.key, w->second);
    }
  }
  fmt::print("expected: {} of row time, about {} wall on {} (the longest row: {})\n", format_duration(total),
             format_duration(std::max(total / jobs, longest)), plural(jobs, "worker"), format_duration(longest));
  return 0;
}

// Stage 4: outputs, the table and the summary from the suite's JSON. Returns the exit code.
int report_run(const std::string& out, const nlohmann::json& j, const RunPlan& rp, Profile profile) {
  write_report_files(out, j);
  print_suite_table(j);
  std::map<std::string, int> n;
  for (auto& r : j["results"]) ++n[r.value("status", "error")];
  const int errors = int(j["case_errors"].size());
  const int fails = n["fail"] + n["error"] + errors;
  fmt::print("{} passed, {} failed{}{}{}\n", n["pass"], fails,
             n["known_failure"] ? fmt::format(", {} known failures (not counted)", n["known_failure"]) : "",
             n["skipped"] ? fmt::format(", {} negative controls skipped (see their rows)", n["skipped"]) : "",
             n["not_run"] ? fmt::format(", {} not run", n["not_run"]) : "");
  if (profile == Profile::quick && !rp.not_run.empty()) {
    size_t controls = 0, known = 0;
    for (auto& [p, why] : rp.not_run) {
      controls += p.kind == "negative_control";
      known += p.kind == "technique";
    }
    fmt::print("quick profile: ran {} of {}; not run: {} and {} (listed in the report as not run, never as "
               "passed; --profile full runs them all)\n",
               rp.run.size(), rp.run.size() + rp.not_run.size(), plural(known, "technique row"),
               plural(controls, "negative control"));
  }
  fmt::print("report: {}/index.html\n", out);
  return fails ? 1 : 0;
}

}  // namespace

int cmd_run(const SuiteOptions& o) {
  set_frames_per_submission(o.frames_per_submission);
  if (o.worker) return run_worker(o);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a row's line reaches a log as soon as it ends
  const std::vector<std::string> devices = split_devices(o.device);
  SuiteSetup s = setup_suite(o, devices.empty() ? "" : devices.front());
  const bool cpu = s.suite.device.type == "cpu";
  if (o.record_timings && !cpu)
    throw std::invalid_argument(fmt::format("--record-timings: expected a CPU device (the timings are lavapipe's), got {}",
                                            s.suite.device.name));
  const Profile profile = resolve_profile(o.profile, cpu && s.tier == Tier::ci);
  RunPlan rp = make_run_plan(o, s.cases, profile);
  // --noise-floor writes each case's golden.json: one process.
  const unsigned jobs = o.noise_floor ? 1u : std::min<unsigned>(resolve_jobs(o.jobs, cpu),
                                                                unsigned(std::max<size_t>(1, rp.run.size())));
  fmt::print("device: {} ({} {}), device class {}, golden class {}, tier {}{}\n", s.suite.device.name,
             s.suite.device.driver_name, s.suite.device.driver_info, s.suite.device_class, s.suite.golden_class,
             s.suite.tier, s.tier == Tier::gpu ? fmt::format(" (references cached in {})", s.cache_root) : "");
  fmt::print("profile {}: {} of {} rows{}, {}\n", profile_name(profile), rp.run.size(),
             rp.run.size() + rp.not_run.size(), rp.shard.is_null() ? "" : fmt::format(" (shard {})", o.shard),
             plural(jobs, "worker"));

  const std::map<std::string, double> recorded = recorded_row_seconds(o.out);
  std::vector<std::pair<std::string, double>> expected;
  for (auto& p : rp.run) expected.push_back({p.key, recorded.count(p.key) ? recorded.at(p.key) : p.cost});
  if (o.dry_run) return print_plan(rp, expected, jobs);
  SuiteProgress progress(expected, jobs, isatty(STDERR_FILENO) != 0);

  nlohmann::json j;
  if (jobs > 1) {
    s.gpu.reset();  // the workers open their own devices
    JobsResult jr = run_jobs(o, s.suite.tier, s.suite.golden_class, cpu, rp.run, jobs, progress);
    j = suite_to_json(s.suite);
    j["results"] = jr.rows;
    j["case_errors"] = jr.case_errors;
    if (!jr.references.empty()) j["references"] = jr.references;
  } else {
    run_serial(s, o, rp.run, progress);
    j = suite_to_json(s.suite);
  }
  for (auto& [p, why] : rp.not_run)
    j["results"].push_back(row_to_json(not_run_row(s.cases[p.case_index], p, planned_run(s.cases, p), why)));
  // Rows in plan order, whatever order they finished in.
  std::map<std::string, size_t> order;
  for (size_t i = 0; i < rp.all.size(); ++i) order[rp.all[i].key] = i;
  std::vector<nlohmann::json> rows = j["results"].get<std::vector<nlohmann::json>>();
  std::stable_sort(rows.begin(), rows.end(),
                   [&](auto& a, auto& b) { return order[row_key_of(a)] < order[row_key_of(b)]; });
  attribute_flagged_rows(o, s.tier, s.cases, rp.run, rows);
  j["results"] = rows;
  if (!rp.shard.is_null()) j["shard"] = rp.shard;
  j["run"] = {{"profile", profile_name(profile)}, {"jobs", jobs}, {"rows_run", rp.run.size()},
              {"rows_not_run", rp.not_run.size()}, {"wall_s", progress.elapsed_s()}};
  j["cases"] = cases_to_json(s.cases);
  progress.print_slowest(10);
  if (o.record_timings) {
    RowSeconds measured;
    for (auto& r : j["results"])
      if (r.value("wall_s", 0.0) > 0)
        measured[row_key_of(r)] = r["wall_s"].get<double>();
    record_row_seconds(o.cases_dir, measured,
                       fmt::format("{} ({}), {}", s.suite.device.name, s.suite.device.driver_info, plural(jobs, "worker")));
    fmt::print("recorded {} row times in {}\n", measured.size(), row_seconds_path(o.cases_dir));
  }
  return report_run(o.out, j, rp, profile);
}

}  // namespace gib
