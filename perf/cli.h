// CLI wiring of `bench` and `perf-diff`, shared by gibench (harness/main.cpp) and gibench-perf
// (perf/main.cpp, no image library) so both take the same options.
#pragma once
#include <CLI/CLI.hpp>

#include "perf/perf.h"

namespace gib::perf {

struct PerfCli {
  BenchOptions bench;
  DiffOptions diff;
  CLI::App* bench_cmd = nullptr;
  CLI::App* diff_cmd = nullptr;
};

inline void add_perf_commands(CLI::App& app, PerfCli& c) {
  auto* b = c.bench_cmd = app.add_subcommand(
      "bench", "time every technique's passes at console-profile workloads; scale to the profiles; noise floor");
  b->add_option("--profile", c.bench.profiles, "profile name(s), comma-separated, or all")->required();
  b->add_option("--technique", c.bench.techniques, "only this technique (repeatable; default: all)");
  b->add_option("--case", c.bench.case_name, "case or scene name (cases/, cases/scenes/; the working folder's, else the source tree's) or JSON path");
  b->add_option("--preset", c.bench.preset, "low | medium | high | ultra");
  b->add_option("--aov", c.bench.aovs,
                "plan only this contract AOV (repeatable; default: every contract AOV the scene supports, so passes "
                "feeding only reflection or another AOV are timed too)");
  b->add_option("--variant", c.bench.variants,
                "LABEL:NAME=VALUE[,NAME=VALUE...]: also time each technique with these options, side by side with "
                "the plain run, and print the per-pass change (repeatable)");
  b->add_option("--frames", c.bench.frames, "timed frames per repeat (default 5 on a CPU device, 30 on a GPU)");
  b->add_option("--repeats", c.bench.repeats, "repeats with a fresh executor (>= 2 for the noise floor)");
  b->add_option("--warmup", c.bench.warmup, "frames before timing (default 1 on a CPU device, 5 on a GPU)");
  b->add_option("--scale-resolution", c.bench.scale_resolution,
                "render at this fraction of the profile's resolution, e.g. 1/8 (default 1 on a GPU, 1/8 on a CPU device)");
  b->add_option("--json", c.bench.json, "write the run (every sample, calibration, scaled costs) as JSON");
  b->add_option("--budget-html", c.bench.budget_html,
                "write each run's per-category budget tree (data/budgets.json, console-scaled) as an HTML page");
  b->add_option("--history", c.bench.history, "append one line per run here (default bench/history.jsonl in the working folder, else the source tree)");
  b->add_flag("--no-history", c.bench.no_history, "do not append to the history file");
  b->add_option("--device", c.bench.device, "device index or name substring");
  b->add_option("--data-dir", c.bench.data_dir, "folder with console-profiles.json and seed-timings.json");
  b->add_option("--calibration-repeats", c.bench.calibration_repeats, "repeats of each calibration kernel");
  b->add_option("--min-change", c.bench.min_change, "smallest change (fraction) worth flagging");

  auto* d = c.diff_cmd = app.add_subcommand(
      "perf-diff", "per pass: is NEW slower than BASE outside noise? (rank test; exit 1 on any regression)");
  d->add_option("base", c.diff.base, "baseline JSON (gibench bench --json, or Google Benchmark JSON)")->required();
  d->add_option("new", c.diff.next, "new JSON")->required();
  d->add_option("--confidence", c.diff.confidence, "confidence level (default 0.95)");
  d->add_option("--min-change", c.diff.min_change, "smallest change (fraction) that counts as a regression (default 0.02)");
}

// -1 when neither command was given.
inline int run_perf_commands(const PerfCli& c) {
  if (c.bench_cmd && c.bench_cmd->parsed()) return cmd_bench(c.bench);
  if (c.diff_cmd && c.diff_cmd->parsed()) return cmd_perf_diff(c.diff);
  return -1;
}

}  // namespace gib::perf
