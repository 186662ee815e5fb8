#include "harness/evaluate.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "harness/case_render.h"
#include "harness/image_io.h"
#include "harness/measure.h"
#include "harness/report.h"
#include "harness/tier.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace fs = std::filesystem;

namespace gib {

namespace {


// The reference of `aov` for evaluation frame `frame` (its own file when the case has
// per-frame references; otherwise the one reference).
const FloatImage& reference_for(CaseContext& ctx, const std::string& aov, uint32_t frame) {
  std::string stem = GoldenStore::reference_stem(aov, ctx.c.output, per_frame_references(ctx.c) ? frame : 0);
  auto it = ctx.references.find(stem);
  if (it != ctx.references.end()) return it->second;
  std::string path = ctx.refs.find(stem, "");
  if (path.empty())
    throw GoldenError(ctx.tier == "gpu"
        ? fmt::format("{}/{}.exr: reference missing from the cache; render it with: gibench references --case {}",
                      ctx.refs.dir(), stem, ctx.c.name)
        : fmt::format("{}/{}.exr: golden missing; create it with: gibench update-goldens --case {} --reference "
                      "--reason \"initial reference\"", ctx.refs.dir(), stem, ctx.c.name));
  return ctx.references[stem] = ctx.refs.read(path);
}


void save_images(const SuiteOptions& o, const std::string& id, const FloatImage& img, const FloatImage* ref,
                 const Case& c) {
  fs::path dir = fs::path(o.out) / "img";
  write_exr((dir / (id + ".exr")).string(), img);
  write_report_image((dir / id).string(), img);
  if (ref) {
    FlipResult f = flip(*ref, img, flip_options(c));
    write_report_error_map((dir / (id + ".flip")).string(), f.error_map);
  }
}

}  // namespace

namespace {

// One row's evaluation, step by step; evaluate_row below runs the steps in order.
struct RowEvaluation {
  RowEvaluation(CaseContext& ctx_, Gpu& gpu_, const TechniqueRun& run_, const std::string& preset_,
                const RowProgress& progress_)
      : ctx(ctx_), gpu(gpu_), run(run_), preset(preset_), progress(progress_), c(ctx_.c),
        aov(run_.compare_aov.empty() ? c.output : run_.compare_aov), frames(evaluation_frames(c)),
        last(frames.back()) {}

  CaseContext& ctx;
  Gpu& gpu;
  const TechniqueRun& run;
  const std::string& preset;
  const RowProgress& progress;
  const Case& c;
  const std::string aov;
  const std::vector<uint32_t> frames;
  const uint32_t last;
  Evaluation e;
  ResultRow& row = e.row;
  CaseRender r;
  const FloatImage* ref = nullptr;  // the reference (or analytic image) at the last frame
  MetricSeries series;
  std::optional<FloatImage> golden, rounded_output;  // rounded_output: the output as a half golden stores it
  bool golden_half = false;
  std::map<std::string, CaseRender> variants;
  metrics::NonFinite nf;

  FrameProgress frames_of(const std::string& what) const {
    if (!progress) return {};
    const RowProgress* p = &progress;
    return [p, what](uint32_t done, uint32_t total) { (*p)(what, done, total); };
  }

  void render(const std::string& kind, const std::string& control_name) {
    row.case_name = c.name;
    row.technique = run.name();
    row.preset = preset;
    row.kind = kind;
    row.options = run.options;
    row.device = gpu.info().name;
    r = render_case(gpu, c, run, preset, 0, 0, ctx.o.stability_scan, frames_of(""));
    row.gpu_ms = r.frame_median_ms;
    row.timing = r.timing;
    // A GPU that lowered its clock during the timed frames inflates their times: say so (the
    // verdict does not depend on times).
    if (r.timing.clock.measured() && r.timing.clock.ratio() > kClockDropWarn)
      row.messages.push_back(fmt::format(
          "GPU clock below its peak around the timed frames: a fixed probe dispatch ran {:.2f}x slower than its "
          "fastest on this device, so these GPU times may be inflated up to that factor (perf/clock_probe.h)",
          r.timing.clock.ratio()));
    row.scanned = r.scanned;
    row.stability = r.stability;
    row.passes = r.passes;
    row.plan = r.plan;
    row.texture_bytes = r.texture_bytes;
    row.curve = r.curve;
    if (c.convergence) row.curve_target = c.convergence->target;
    // Controls are named in the id: two controls of one technique and preset must not share files.
    row.image_id = fmt::format("{}__{}.{}{}", c.name, run.name(), preset,
                               kind == "negative_control" ? ".negative-" + control_name : "");
    row.eval_frames = frames;
    // Only cases with a path-traced reference have its image (variant-only and analytic cases do not).
    row.reference_id = c.reference_spp ? fmt::format("{}__reference.{}", c.name, aov) : "";
    series = MetricSeries{r.curve.empty() ? nullptr : &r.curve, r.last_frames.size() < 2 ? nullptr : &r.last_frames,
                          r.scanned ? &r.stability : nullptr, r.nan_pixels.empty() ? nullptr : &r.nan_pixels};
  }

  // Metrics recorded whether or not a threshold uses them (cases without a reference: against
  // the analytic image, when there is one).
  void always_on_metrics() {
    const FloatImage& final_image = image_at(r, last, c);
    ref = c.reference_spp ? &reference_for(ctx, aov, last) : (ctx.analytic ? &*ctx.analytic : nullptr);
    if (ref) {
      row.metrics["flip_vs_reference"] = compute_metric(c, "flip", final_image, ref, nullptr);
      row.metrics["psnr_vs_reference"] = compute_metric(c, "psnr", final_image, ref, nullptr);
      row.metrics["relmse_vs_reference"] = compute_metric(c, "relmse", final_image, ref, nullptr);
      // Every ROI's ratio to the path-traced reference at the last frame, so rows without an
      // accuracy bound (ablations such as probe-volume's per-mitigation rows) still record it;
      // a roi_ratio threshold replaces the value with its worst over the evaluated frames.
      if (c.reference_spp)
        for (const Roi& roi : c.rois)
          row.metrics["roi_ratio_vs_reference_" + roi.name] = compute_metric(c, "roi_ratio", final_image, ref, &roi);
    }
    if (series.frames) row.metrics["flicker"] = metrics::flicker(r.last_frames);
    if (series.nan_pixels)
      for (const char* m : {"nan_frames", "nan_last_frame", "nan_max_pixels"})
        row.metrics[m] = compute_metric(c, m, r.image, nullptr, nullptr, series);
    if (series.stability)
      for (const auto& [m, categories] : scan_metrics())
        row.metrics[m] = compute_metric(c, m, r.image, nullptr, nullptr, series);
    if (series.curve)
      for (const char* m : {"conv_error_final", "conv_error_max", "conv_drift", "conv_oscillation"})
        row.metrics[m] = compute_metric(c, m, final_image, nullptr, nullptr, series);
    for (const auto& [name, value] : r.stats) row.metrics["stat_" + name] = value;
    nf = metrics::count_non_finite(r.image);
    row.metrics["nan_count"] = double(nf.nan);
    row.metrics["inf_count"] = double(nf.inf);
  }

  // A technique row against its approved golden: FLIP within the case's bound, and the count of
  // differing values (every technique is bit-identical run to run on one device and driver).
  void compare_with_golden() {
    std::string stem = GoldenStore::technique_stem(run.name(), preset);
    std::string path = ctx.store.find(stem, ctx.golden_cls);
    if (path.empty()) {
      row.messages.push_back(fmt::format(
          "{}/{}.exr: golden missing; create it with: gibench update-goldens --case {} --technique {}{} --reason "
          "\"initial golden\"",
          ctx.store.dir(), stem, c.name, run.technique, ctx.tier == "gpu" ? " --tier gpu" : ""));
      e.failed = true;
      return;
    }
    golden = ctx.store.read(path, &golden_half);
    row.golden_class =
        fs::path(path).filename() == ctx.store.file_name(stem, ctx.golden_cls) ? ctx.golden_cls : "lavapipe";
    if (row.golden_class != ctx.golden_cls)
      row.messages.push_back(fmt::format(
          "compared with the {} golden ({}): no {} golden is approved for this run; approve one on a device of that "
          "class with: gibench update-goldens --case {} --technique {} --reason \"...\"",
          row.golden_class, fs::path(path).filename().string(), ctx.golden_cls, c.name, run.technique));
    // A half-float golden (the GPU tier's) stores the output rounded to half: compare the output
    // rounded the same way, so an unchanged technique differs in no value.
    if (golden_half) rounded_output = round_to_half(r.image);
    const FloatImage& out = golden_half ? *rounded_output : r.image;
    Threshold gt{"flip", "golden", "", c.golden_flip_max, std::nullopt};
    CheckResult cr = check_value(gt, compute_metric(c, "flip", out, &*golden, nullptr), 0);
    row.metrics["flip_vs_golden"] = cr.value;
    size_t differ = 0;
    double worst = 0;
    if (golden->pixels.size() == out.pixels.size())
      for (size_t i = 0; i < out.pixels.size(); ++i)
        if (std::memcmp(&golden->pixels[i], &out.pixels[i], sizeof(float)) != 0) {
          ++differ;
          worst = std::max(worst, std::abs(double(golden->pixels[i]) - double(out.pixels[i])));
        }
    row.metrics["golden_differing_values"] =
        golden->pixels.size() == out.pixels.size() ? double(differ) : double(out.pixels.size());
    row.metrics["golden_max_abs_diff"] = worst;
    row.checks.push_back(cr);
    e.failed |= !cr.pass;
  }

  // A variant: the same technique and preset with other options, rendered once.
  const CaseRender& variant(const std::string& name) {
    auto it = variants.find(name);
    if (it != variants.end()) return it->second;
    TechniqueRun v = run;
    for (auto& [k, val] : run.variants.at(name)) v.options[k] = val;
    return variants[name] = render_case(gpu, c, v, preset, 0, 0, false, frames_of("variant " + name));
  }

  // Whether a threshold is checked outside the image loop (skipped, a counter, a missing golden).
  bool check_special(const Threshold& t) {
    if (t.metric.rfind("scan_", 0) == 0 && !series.stability) {
      CheckResult skipped{t.metric, t.against, t.roi, 0, t.max, t.min, true, true,
                          fmt::format("{} skipped: the stability scan did not run (--no-stability-scan)", t.metric)};
      row.messages.push_back(skipped.message);
      row.checks.push_back(std::move(skipped));
      return true;
    }
    if (t.metric.rfind("stat_", 0) == 0) {
      // A technique's GPU counter (Technique::stats), read after the last frame.
      auto it = r.stats.find(t.metric.substr(5));
      if (it == r.stats.end())
        throw CaseError(fmt::format(
            "{}: {} {}: metric {} is not counted in this run (its pass does not run with these options)", c.file,
            run.technique, preset, t.metric));
      CheckResult cr = check_value(t, it->second, 0);
      row.checks.push_back(cr);
      e.failed |= !cr.pass;
      return true;
    }
    if (t.against == "golden" && !golden) {  // the row has failed on the missing golden already
      CheckResult missing{t.metric, t.against, t.roi, std::numeric_limits<double>::quiet_NaN(), t.max, t.min, false,
                          false, fmt::format("{} vs golden: no approved golden to compare with", t.metric)};
      row.checks.push_back(std::move(missing));
      e.failed = true;
      return true;
    }
    return false;
  }

  // Every threshold of the run; image metrics at every evaluation frame (the worst counts),
  // series metrics and the golden once.
  void check_thresholds() {
    for (auto& t : run.thresholds) {
      if (check_special(t)) continue;
      const Roi* roi = t.roi.empty() ? nullptr : find_roi(c, t.roi);
      bool once = t.metric == "flicker" || t.metric.rfind("conv_", 0) == 0 || t.metric.rfind("scan_", 0) == 0 ||
                  (t.metric.rfind("nan_", 0) == 0 && t.metric != "nan_count") || t.against == "golden";
      std::vector<uint32_t> at = once ? std::vector<uint32_t>{last} : frames;
      if (t.frame) at = {t.frame};
      std::string key = t.metric + (t.against.empty() ? "" : "_vs_" + t.against) + (t.roi.empty() ? "" : "_" + t.roi);
      CheckResult worst;
      double worst_violation = -std::numeric_limits<double>::infinity();
      for (uint32_t f : at) {
        const FloatImage* out = &image_at(r, f, c);
        const FloatImage* against = nullptr;
        if (t.against == "reference") against = &reference_for(ctx, aov, f);
        else if (t.against == "golden") against = &*golden, out = golden_half ? &*rounded_output : out;
        else if (t.against == "analytic") against = ctx.analytic ? &*ctx.analytic : nullptr;
        else if (t.against.rfind("variant:", 0) == 0) against = &image_at(variant(t.against.substr(8)), f, c);
        double v = compute_metric(c, t.metric, *out, against, roi, series);
        if (at.size() > 1) row.metrics[fmt::format("{}@f{}", key, f)] = v;
        double viol = violation(t, v);
        if (viol > worst_violation || f == at.front()) {
          worst_violation = viol;
          worst = check_value(t, v, at.size() > 1 ? f : 0);
        }
      }
      row.metrics[key] = worst.value;
      row.checks.push_back(worst);
      e.failed |= !worst.pass;
    }
  }

  // Messages of the failed checks and the scan's first offenders; the report's images.
  void finish() {
    if (nf.nan || nf.inf) {
      row.messages.push_back(fmt::format("output has {} NaN and {} Inf values", nf.nan, nf.inf));
      e.failed = true;
    }
    for (auto& cr : row.checks)
      if (!cr.pass) row.messages.push_back(cr.message);
    // First offenders are reported on every row (a threshold on scan_* decides pass/fail).
    for (auto& line : row.stability.first_offender_lines()) row.messages.push_back("stability: " + line);
    save_images(ctx.o, row.image_id, image_at(r, last, c), ref, c);
    for (auto& [name, vr] : variants)
      save_images(ctx.o, row.image_id + ".variant-" + name, image_at(vr, last, c), ref, c);
    for (auto& [name, img] : r.views) {
      row.views.push_back({name, row.image_id + ".view-" + name});
      save_images(ctx.o, row.views.back().second, img, nullptr, c);
    }
    row.printouts = r.printouts;
  }
};

}  // namespace

Evaluation evaluate_row(CaseContext& ctx, Gpu& gpu, const TechniqueRun& run, const std::string& preset,
                        const std::string& kind, const std::string& control_name, const RowProgress& progress) {
  RowEvaluation ev(ctx, gpu, run, preset, progress);
  ev.render(kind, control_name);
  ev.always_on_metrics();
  if (kind == "technique") ev.compare_with_golden();
  ev.check_thresholds();
  ev.finish();
  return std::move(ev.e);
}

void check_noise_floor(CaseContext& ctx, Gpu& gpu) {
  const Case& c = ctx.c;
  if (c.reference_spp == 0) return;  // no reference, no floor
  nlohmann::json meta = ctx.refs.metadata();
  if (ctx.o.noise_floor) {
    Case at_spp = c;
    at_spp.reference_spp = recorded_reference_spp(c, meta);
    nlohmann::json floor = measure_noise_floor(gpu, at_spp);
    record_noise_floor(meta, floor);
    ctx.refs.write_metadata(meta);
    fmt::print("{}: noise floor (FLIP between two seeds at {} spp) {:.6f}\n", c.name, floor["spp"].get<uint32_t>(),
               floor["flip"].get<double>());
  }
  check_noise_floor_bounds(c, meta, (fs::path(ctx.refs.dir()) / "golden.json").string());
}

void write_reference_previews(const CaseContext& ctx) {
  const Case& c = ctx.c;
  uint32_t at = per_frame_references(c) ? evaluation_frames(c).back() : 0;
  for (auto& aov : compared_aovs(c)) {
    auto it = ctx.references.find(GoldenStore::reference_stem(aov, c.output, at));
    if (it != ctx.references.end())
      write_report_image((fs::path(ctx.o.out) / "img" / fmt::format("{}__reference.{}", c.name, aov)).string(),
                         it->second);
  }
}

}  // namespace gib
