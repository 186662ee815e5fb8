// gibench: the command line. Every error becomes one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <exception>

#include "harness/attribution/attribute_command.h"
#include "harness/compare.h"
#include "perf/cli.h"
#include "harness/render.h"
#include "harness/suite.h"
#include "harness/shard.h"
#include "harness/sweep.h"
#include "harness/report_check.h"
#include "harness/timing.h"
#include "harness/references.h"

namespace {

void add_suite_options(CLI::App* app, gib::SuiteOptions& o) {
  app->add_option("--case", o.case_globs, "case name or glob (repeatable; default: all)");
  app->add_option("--cases-dir", o.cases_dir, "folder of case JSON files");
  app->add_option("--goldens", o.goldens_dir, "goldens folder");
  app->add_option("--out", o.out, "output folder");
  app->add_option("--device", o.device, "device index or name substring");
  app->add_flag("--validate", o.validate, "Vulkan validation on; any message fails the run");
  app->add_option("--tier", o.tier, "ci | gpu: case sizes, references and goldens (default: ci on lavapipe, gpu elsewhere)");
  app->add_option("--reference-cache", o.reference_cache,
                  "GPU tier's reference cache (default $GIBENCH_REFERENCE_CACHE, else ~/.cache/gibench/references)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gibench: rendering test and benchmark harness for real-time GI"};
  app.require_subcommand(1);

  std::string resource_spec;
  app.add_subcommand("devices", "list Vulkan devices and which one is the default")
      ->add_option("--ctest-resource-spec", resource_spec,
                   "also write a CTest resource spec (one 'gpus' slot per GPU) for the sharded suite");

  gib::RenderOptions ro;
  auto* render = app.add_subcommand("render", "render a scene with a technique");
  render->add_option("--scene", ro.scene, "scene JSON file")->required();
  render->add_option("--technique", ro.technique, "direct | reference");
  render->add_option("--preset", ro.preset, "low | medium | high | ultra");
  render->add_option("--spp", ro.spp, "reference: samples per pixel in total (default 64)");
  render->add_option("--frames", ro.frames, "frames to run (temporal techniques, timing)");
  std::string size = "256x144";
  render->add_option("--size", size, "render size WxH");
  render->add_option("--seed", ro.seed, "random seed");
  render->add_option("--device", ro.device, "device index or name substring");
  render->add_flag("--validate", ro.validate, "enable Vulkan validation; messages fail the run");
  render->add_flag("--plan", ro.plan_only, "print the plan (ran / culled and why) and exit");
  render->add_option("--dump-graph", ro.dot, "write the graph as graphviz .dot");
  render->add_option("--dump", ro.dumps, "also write this resource as EXR (repeatable)");
  render->add_option("--option", ro.options, "technique option NAME=VALUE, e.g. world_offset_x=10000 (repeatable)");
  render->add_option("--out", ro.out, "output EXR (a PNG preview is written beside it)");
  render->add_option("--json", ro.json, "write device, plan and timings as JSON");

  gib::SuiteOptions run_opts;
  auto* run = app.add_subcommand("run", "run the scenario suite: cases vs references and goldens, report");
  add_suite_options(run, run_opts);
  run->add_flag("!--no-stability-scan", run_opts.stability_scan,
                "skip the GPU scan of every resource each pass writes for NaN, Inf, negative and out-of-bound values");
  run->add_option("--shard", run_opts.shard,
                  "K/N: run the rows i with i % N == K (0-based; default: GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS if set)");
  run_opts.profile = "";
  run_opts.jobs = 0;
  run->add_option("--profile", run_opts.profile,
                  "quick | full: quick runs a subset touching every case and technique, lists the rest as not run "
                  "(default: quick on lavapipe at the CI tier, full elsewhere)");
  run->add_option("-j,--jobs", run_opts.jobs,
                  "rows rendered at once, one worker process each (default 0: one per core on a CPU device, "
                  "8 on a GPU; --device 0,1 spreads them over GPUs)");
  run->add_option("--frames-per-submission", run_opts.frames_per_submission,
                  "GPU: frames of a row recorded into one submission between the host's reads of its output "
                  "(default 64; 1: a submit-and-wait per frame; same output at any value)")
      ->check(CLI::Range(1u, 4096u));
  run->add_flag("--record-timings", run_opts.record_timings,
                "write each row's wall seconds into cases/timings/lavapipe.json (the quick profile's costs; CPU device)");
  run->add_flag("--dry-run", run_opts.dry_run,
                "print the plan: each row, run or not and why, its expected seconds; render nothing");
  run->add_flag("--attribute", run_opts.attribute,
                "after the rows, the error attribution of every row a case flags with \"attribute\": true "
                "(gibench attribute's defaults), its waterfall linked from the report");
  run->add_flag("--worker", run_opts.worker, "internal: a worker of a parallel run (rows on stdin, events on stdout)")
      ->group("");
  run->add_option("--technique", run_opts.techniques,
                  "run only the rows and negative controls of this technique (repeatable; default: all)");
  run->add_option("--golden-class", run_opts.golden_class,
                  "compare with this device class's approved goldens (lavapipe, nvidia, ...; default: the device's)");
  run->add_flag("--noise-floor", run_opts.noise_floor,
                "render each reference twice (two seeds), record the FLIP between them in golden.json");

  gib::UpdateOptions up;
  auto* update = app.add_subcommand("update-goldens", "re-render and replace goldens (atomically, with history)");
  add_suite_options(update, up.suite);
  update->add_option("--technique", up.techniques, "only this technique's goldens (repeatable)");
  update->add_flag("--reference", up.reference, "re-render the path-traced reference");
  update->add_option("--spp", up.spp, "with --reference: samples per pixel (default: the case's reference_spp)")
      ->check(CLI::Range(1u, 1048576u));
  update->add_flag("--noise-floor", up.noise_floor,
                   "with --reference: also render seed + 1000 at the same spp, record the FLIP between them");
  update->add_flag("--only-reference", up.only_reference,
                   "with --reference: render no technique golden (e.g. references rendered on a GPU for every device)");
  update->add_option("--reason", up.reason, "why: recorded in golden.json")->required();
  update->add_option("--from-run", up.from_run,
                     "approve the technique outputs of a finished `gibench run --out DIR` (its device class and tier) "
                     "instead of rendering them again");

  gib::SuiteOptions sweep_opts;
  sweep_opts.out = "out/sweep";
  auto* sweep = app.add_subcommand("sweep", "error against GPU time for every technique x preset of a case");
  add_suite_options(sweep, sweep_opts);
  sweep->add_option("--technique", sweep_opts.techniques,
                    "only the rows of this technique (repeatable; default: every row of the case)");

  gib::TimingOptions timing_opts;
  auto* timing = app.add_subcommand(
      "timing", "time one case x technique x preset as run, sweep and bench do: medians, spread, ratios, same work?");
  add_suite_options(timing, timing_opts.suite);
  timing->add_option("--technique", timing_opts.technique, "technique (default: the case's first run)");
  timing->add_option("--preset", timing_opts.preset, "preset (default: the run's first)");
  timing->add_option("--repeats", timing_opts.repeats, "renders per path, interleaved (default 3)");
  timing->add_option("--frames", timing_opts.frames, "timed frames per render (default: the case's timing_frames)");
  timing->add_option("--bench-warmup", timing_opts.bench_warmup, "bench's warm-up frames (default: the case's frames)");
  timing->add_option("--json", timing_opts.json, "write every sample as JSON");

  gib::SuiteOptions refs_opts;
  bool refresh = false, dry_run = false;
  auto* references = app.add_subcommand(
      "references", "render the GPU tier's path-traced references into the local cache (those missing, or --refresh all)");
  add_suite_options(references, refs_opts);
  references->add_flag("--refresh", refresh, "re-render references already in the cache");
  uint32_t max_spp = 1048576;
  references->add_option("--max-spp", max_spp,
                         "budget: render at most this many spp (a reference short of its floor is kept, marked not "
                         "converged; a later larger budget refines it)")
      ->check(CLI::Range(1u, 1048576u));
  references->add_flag("--dry-run", dry_run, "print each case's size, target floor, start spp and cache key; render nothing");

  gib::AttributeOptions attr;
  auto* attribute = app.add_subcommand(
      "attribute", "error attribution of one case row: each stage's Shapley share of the error, oracles in its place");
  add_suite_options(attribute, attr.suite);
  attribute->add_option("--technique", attr.technique, "technique (required)")->required();
  attribute->add_option("--label", attr.label, "the case run's label (default: the unlabelled run)");
  attribute->add_option("--preset", attr.preset, "preset (default: the run's first)");
  attribute->add_option("--seeds", attr.settings.seeds, "renders per subset of oracles (default 2)")->check(CLI::Range(1u, 64u));
  attribute->add_option("--oracle-seeds", attr.settings.oracle_seeds, "renders the seed-mean oracles average (default 4)")
      ->check(CLI::Range(1u, 64u));
  attribute
      ->add_option("--oracle-frames", attr.settings.oracle_frames,
                   "the seed-mean oracles average each oracle render's last N frames too (a still scene, or one "
                   "frozen at an evaluation frame; default 16)")
      ->check(CLI::Range(1u, 1024u));
  attribute->add_option("--noise-spp", attr.settings.noise_spp,
                        "spp of the two reference renders the noise floor is scaled from (default 16)")
      ->check(CLI::Range(1u, 65536u));

  std::string report_dir = "out";
  auto* check_report = app.add_subcommand(
      "check-report", "open DIR/index.html in headless Chromium; exit 1 on an error banner or console output");
  check_report->add_option("dir", report_dir, "the report's folder (default out)");

  gib::MergeOptions mo;
  auto* merge = app.add_subcommand("merge", "merge the outputs of `run --shard K/N` into one results.json, junit.xml and report");
  merge->add_option("--out", mo.out, "output folder (default out)");
  merge->add_option("shards", mo.shard_dirs, "the shards' output folders")->required();

  gib::CompareOptions co;
  auto* compare = app.add_subcommand("compare", "FLIP, PSNR and relMSE of two images");
  compare->add_option("reference", co.reference, "reference image (EXR or PNG)")->required();
  compare->add_option("test", co.test, "test image")->required();
  bool force_hdr = false, force_ldr = false;
  compare->add_flag("--hdr", force_hdr, "HDR-FLIP (default for .exr references)");
  compare->add_flag("--ldr", force_ldr, "LDR-FLIP (default otherwise)");
  compare->add_option("--ppd", co.ppd, "pixels per degree");
  compare->add_option("--tonemapper", co.tonemapper, "aces | reinhard | hable");
  std::vector<double> exposure;
  compare->add_option("--exposure", exposure, "START STOP N: HDR exposure range")->expected(3);
  compare->add_option("--error-map", co.error_map, "write the magma error map PNG");
  compare->add_flag("--json", co.json, "print one JSON object");

  gib::perf::PerfCli perf;
  gib::perf::add_perf_commands(app, perf);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("devices")) return gib::cmd_devices(resource_spec);
    if (int rc = gib::perf::run_perf_commands(perf); rc >= 0) return rc;
    if (app.got_subcommand("run")) {
      if (gib::Shard s = gib::shard_from(run_opts.shard); s.active())
        run_opts.shard = std::to_string(s.index) + "/" + std::to_string(s.count);
      return gib::cmd_run(run_opts);
    }
    if (app.got_subcommand("update-goldens")) return gib::cmd_update_goldens(up);
    if (app.got_subcommand("sweep")) return gib::cmd_sweep(sweep_opts);
    if (app.got_subcommand("references")) return gib::cmd_references(refs_opts, refresh, dry_run, max_spp);
    if (app.got_subcommand("timing")) return gib::cmd_timing(timing_opts);
    if (app.got_subcommand("attribute")) return gib::cmd_attribute(attr);
    if (app.got_subcommand("check-report")) return gib::cmd_check_report(report_dir);
    if (app.got_subcommand("merge")) return gib::cmd_merge(mo);
    if (app.got_subcommand("compare")) {
      if (force_hdr && force_ldr) throw std::invalid_argument("compare: expected at most one of --hdr and --ldr");
      if (force_hdr || force_ldr) co.hdr = force_hdr;
      if (!exposure.empty()) {
        if (exposure[2] < 1 || exposure[2] != double(int(exposure[2])))
          throw std::invalid_argument(fmt::format("--exposure: expected N as a positive integer, got {}", exposure[2]));
        co.start_exposure = exposure[0];
        co.stop_exposure = exposure[1];
        co.num_exposures = int(exposure[2]);
      }
      return gib::cmd_compare(co);
    }
    if (app.got_subcommand("render")) {
      unsigned w = 0, h = 0;
      char x = 0;
      if (std::sscanf(size.c_str(), "%u%c%u", &w, &x, &h) != 3 || x != 'x' || w == 0 || h == 0 || w > 16384 || h > 16384)
        throw std::invalid_argument(fmt::format("--size: expected WxH like 256x144, got '{}'", size));
      ro.width = w;
      ro.height = h;
      return gib::cmd_render(ro);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "gibench: error: {}\n", e.what());
    return 2;
  }
  return 0;
}
