#include "harness/runner.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fnmatch.h>
#include <limits>
#include <set>

#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/shard.h"
#include "harness/tier.h"

#include <cstring>
#include "harness/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "harness/report.h"
#include "renderer/techniques/technique.h"

namespace fs = std::filesystem;

namespace gib {

int SuiteResult::failures() const {
  int n = static_cast<int>(case_errors.size());
  for (auto& r : rows) n += r.status != "pass" && r.status != "known_failure" && r.status != "skipped";
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

namespace {

FlipOptions flip_options(const Case& c) {
  FlipOptions f;
  f.ppd = c.ppd;
  f.mode = c.flip_mode == "ldr" ? FlipOptions::Mode::ldr : FlipOptions::Mode::hdr;
  return f;
}

const Roi* find_roi(const Case& c, const std::string& name) {
  for (auto& r : c.rois)
    if (r.name == name) return &r;
  return nullptr;
}

// Mean of a 1-channel map inside a normalised box.
double roi_mean(const FloatImage& map, const Roi& r) {
  double sum = 0;
  size_t n = 0;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      float u = (x + 0.5f) / map.width, v = (y + 0.5f) / map.height;
      if (u >= r.x0 && u < r.x1 && v >= r.y0 && v < r.y1) {
        sum += map.at(x, y, 0);
        ++n;
      }
    }
  if (!n) throw CaseError(fmt::format("roi '{}' covers no pixel at {}x{}", r.name, map.width, map.height));
  return sum / double(n);
}

FloatImage crop(const FloatImage& img, const Roi* r) {
  if (!r) return img;
  uint32_t x0 = uint32_t(std::floor(r->x0 * img.width)), x1 = uint32_t(std::ceil(r->x1 * img.width));
  uint32_t y0 = uint32_t(std::floor(r->y0 * img.height)), y1 = uint32_t(std::ceil(r->y1 * img.height));
  x1 = std::min(x1, img.width);
  y1 = std::min(y1, img.height);
  FloatImage out(x1 - x0, y1 - y0, img.channels);
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x)
      for (uint32_t ch = 0; ch < img.channels; ++ch) out.at(x - x0, y - y0, ch) = img.at(x, y, ch);
  return out;
}

std::string fmt_value(double v) { return std::isinf(v) ? "inf" : fmt::format("{:.4g}", v); }


// The stability scan's case metrics, each the sum of its categories over every frame, pass and
// resource (compute_metric and the per-row scan_* metrics both read this).
const std::vector<std::pair<std::string, std::vector<StabilityCategory>>>& scan_metrics() {
  static const std::vector<std::pair<std::string, std::vector<StabilityCategory>>> m = {
      {"scan_nan", {StabilityCategory::nan}},
      {"scan_inf", {StabilityCategory::pos_inf, StabilityCategory::neg_inf}},
      {"scan_negative", {StabilityCategory::negative}},
      {"scan_above_max", {StabilityCategory::above_max}},
      {"scan_saturated", {StabilityCategory::saturated}}};
  return m;
}
}  // namespace

double convergence_metric(const std::string& metric, const std::vector<double>& m, double target,
                          uint32_t settle_frame) {
  if (m.empty()) throw CaseError(fmt::format("metric '{}': no convergence curve was recorded", metric));
  if (!(target > 0)) throw CaseError(fmt::format("metric '{}': target must be > 0, got {}", metric, target));
  size_t from = std::min<size_t>(settle_frame ? settle_frame - 1 : 0, m.size() - 1);
  auto rel = [&](double v) { return std::abs(v - target) / target; };
  if (metric == "conv_error_final") return rel(m.back());
  if (metric == "conv_error_max") {
    double worst = 0;
    for (size_t i = from; i < m.size(); ++i) worst = std::isnan(m[i]) ? m[i] : std::max(worst, rel(m[i]));
    return worst;
  }
  size_t n = m.size() - from;
  if (metric == "conv_drift") {
    size_t k = std::max<size_t>(1, n / 10);
    double a = 0, b = 0;
    for (size_t i = 0; i < k; ++i) {
      a += m[from + i];
      b += m[m.size() - 1 - i];
    }
    return std::abs(b - a) / double(k) / target;
  }
  if (metric == "conv_oscillation") {
    // 5-frame trailing mean, so per-frame noise of a stochastic technique does not read as
    // oscillation; then the total variation beyond the net change.
    std::vector<double> smooth;
    for (size_t i = from; i < m.size(); ++i) {
      size_t lo = i >= from + 4 ? i - 4 : from;
      double sum = 0;
      for (size_t j = lo; j <= i; ++j) sum += m[j];
      smooth.push_back(sum / double(i - lo + 1));
    }
    double tv = 0;
    for (size_t i = 1; i < smooth.size(); ++i) tv += std::abs(smooth[i] - smooth[i - 1]);
    return (tv - std::abs(smooth.back() - smooth.front())) / target;
  }
  throw CaseError(fmt::format("unknown convergence metric '{}'", metric));
}

double compute_metric(const Case& c, const std::string& metric, const FloatImage& output, const FloatImage* against,
                      const Roi* roi, const MetricSeries& series) {
  auto need = [&]() -> const FloatImage& {
    if (!against) throw CaseError(fmt::format("{}: metric '{}' needs an image to compare against", c.file, metric));
    if (against->width != output.width || against->height != output.height)
      throw CaseError(fmt::format("{}: metric '{}': output {}x{} vs comparison image {}x{}", c.file, metric,
                                  output.width, output.height, against->width, against->height));
    return *against;
  };
  if (metric == "flip") {
    FlipResult f = flip(need(), output, flip_options(c));
    return roi ? roi_mean(f.error_map, *roi) : f.mean;
  }
  if (metric == "psnr") return metrics::psnr(crop(need(), roi), crop(output, roi));
  if (metric == "relmse") return metrics::relmse(crop(need(), roi), crop(output, roi));
  if (metric == "max_abs_error") return metrics::max_abs_error(crop(need(), roi), crop(output, roi));
  if (metric == "roi_mean") {
    Roi all{"", 0, 0, 1, 1};
    const Roi& r = roi ? *roi : all;
    return metrics::roi_mean_luminance(output, r.x0, r.y0, r.x1, r.y1);
  }
  if (metric == "roi_ratio") {
    Roi all{"", 0, 0, 1, 1};
    const Roi& r = roi ? *roi : all;
    double den = metrics::roi_mean_luminance(need(), r.x0, r.y0, r.x1, r.y1);
    return metrics::roi_mean_luminance(output, r.x0, r.y0, r.x1, r.y1) / std::max(den, 1e-30);
  }
  metrics::Roi mroi = roi ? metrics::Roi{roi->x0, roi->y0, roi->x1, roi->y1} : metrics::Roi{};
  if (metric == "uv_shift_max") return metrics::max_chromaticity_shift(need(), output, mroi);
  if (metric == "banding") return metrics::banding_index(output, mroi);
  if (metric == "penumbra_width_error") {
    if (!roi) throw CaseError(fmt::format("{}: metric 'penumbra_width_error' needs a roi (a band across the shadow edge)", c.file));
    return metrics::penumbra_width_error(need(), output, mroi);
  }
  if (metric == "banding_excess") return metrics::banding_index(output, mroi) - metrics::banding_index(need(), mroi);
  if (metric == "flicker") {
    if (!series.frames || series.frames->size() < 2)
      throw CaseError(fmt::format("{}: metric 'flicker' needs the last frames (flicker_frames >= 2)", c.file));
    return metrics::flicker(*series.frames, mroi);
  }
  if (metric.rfind("conv_", 0) == 0) {
    if (!series.curve || !c.convergence)
      throw CaseError(fmt::format("{}: metric '{}' needs a convergence curve (top-level \"convergence\")", c.file, metric));
    return convergence_metric(metric, *series.curve, c.convergence->target, c.convergence->settle_frame);
  }
  if (metric == "nan_frames" || metric == "nan_last_frame" || metric == "nan_max_pixels") {
    if (!series.nan_pixels)
      throw CaseError(fmt::format("{}: metric '{}' needs per-frame NaN counts (top-level \"track_nan\": true)", c.file,
                                  metric));
    double frames = 0, last = 0, most = 0;
    for (size_t i = 0; i < series.nan_pixels->size(); ++i) {
      double n = (*series.nan_pixels)[i];
      if (n > 0) {
        ++frames;
        last = double(i + 1);
      }
      most = std::max(most, n);
    }
    return metric == "nan_frames" ? frames : metric == "nan_last_frame" ? last : most;
  }
  if (metric.rfind("scan_", 0) == 0) {
    if (!series.stability)
      throw CaseError(fmt::format("{}: metric '{}' needs the stability scan (gibench run without --no-stability-scan)",
                                  c.file, metric));
    for (const auto& [name, categories] : scan_metrics())
      if (metric == name) {
        uint64_t n = 0;
        for (StabilityCategory cat : categories) n += series.stability->total(cat);
        return double(n);
      }
  }
  if (metric == "nan_count") return double(metrics::count_non_finite(crop(output, roi)).nan);
  if (metric == "inf_count") return double(metrics::count_non_finite(crop(output, roi)).inf);
  throw CaseError(fmt::format("{}: unknown metric '{}'", c.file, metric));
}

namespace {

struct CaseContext {
  const Case& c;
  GoldenStore store;       // approved technique goldens of the tier
  GoldenStore refs;        // the references of the tier (committed, or the GPU tier's cache entry)
  std::string tier;
  std::string cls;         // the device's class: known failures
  std::string golden_cls;  // whose approved technique goldens rows are compared with
  std::map<std::string, FloatImage> references;  // by AOV
  std::optional<FloatImage> analytic;
  const SuiteOptions& o;
};

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

// How far a value lies outside a threshold's bounds (<= 0 inside; NaN counts as infinitely far).
double violation(const Threshold& t, double v) {
  if (std::isnan(v)) return std::numeric_limits<double>::infinity();
  double out = -std::numeric_limits<double>::infinity();
  if (t.max) out = std::max(out, v - *t.max);
  if (t.min) out = std::max(out, *t.min - v);
  return out;
}

CheckResult check_value(const Threshold& t, double value, uint32_t frame) {
  CheckResult r;
  r.metric = t.metric;
  r.against = t.against;
  r.roi = t.roi;
  r.max = t.max;
  r.min = t.min;
  r.value = value;
  std::string what = fmt::format("{}{}{}{}", t.metric, t.against.empty() ? "" : " vs " + t.against,
                                 t.roi.empty() ? "" : " in " + t.roi, frame ? fmt::format(" at frame {}", frame) : "");
  if (std::isnan(r.value)) {
    r.pass = false;
    r.message = what + " is NaN";
  } else if (t.max && r.value > *t.max) {
    r.pass = false;
    r.message = fmt::format("{} {} > max {} (by {})", what, fmt_value(r.value), fmt_value(*t.max),
                            fmt_value(r.value - *t.max));
  } else if (t.min && r.value < *t.min) {
    r.pass = false;
    r.message = fmt::format("{} {} < min {} (by {})", what, fmt_value(r.value), fmt_value(*t.min),
                            fmt_value(*t.min - r.value));
  } else {
    r.message = fmt::format("{} {} ok", what, fmt_value(r.value));
  }
  return r;
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

// The image a run produced at 1-based frame f (its final image at the last frame).
const FloatImage& image_at(const CaseRender& r, uint32_t f, const Case& c) {
  if (f == c.frames) return r.image;
  auto it = r.frame_images.find(f);
  if (it == r.frame_images.end()) throw CaseError(fmt::format("{}: frame {} was not captured", c.file, f));
  return it->second;
}

ResultRow evaluate(CaseContext& ctx, Gpu& gpu, const TechniqueRun& run, const std::string& preset,
                   const std::string& kind, const std::string& control_name = "") {
  ResultRow row;
  row.case_name = ctx.c.name;
  row.technique = run.name();
  row.preset = preset;
  row.kind = kind;
  row.options = run.options;
  row.device = gpu.info().name;
  const Case& c = ctx.c;
  std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  CaseRender r = render_case(gpu, c, run, preset, 0, 0, ctx.o.stability_scan);
  row.gpu_ms = r.frame_median_ms;
  row.timing = r.timing;
  // A GPU that lowered its clock during the timed frames inflates their times: say so (the
  // verdict does not depend on times).
  if (r.timing.clock.measured() && r.timing.clock.ratio() > kClockDropWarn)
    row.messages.push_back(fmt::format(
        "GPU clock below its peak around the timed frames: a fixed probe dispatch ran {:.2f}x slower than its fastest "
        "on this device, so these GPU times may be inflated up to that factor (perf/clock_probe.h)",
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
  const std::vector<uint32_t> frames = evaluation_frames(c);
  row.eval_frames = frames;
  const uint32_t last = frames.back();
  // Only cases with a path-traced reference have its image (variant-only and analytic cases do not).
  row.reference_id = c.reference_spp ? fmt::format("{}__reference.{}", c.name, aov) : "";
  bool failed = false;
  const FloatImage& final_image = image_at(r, last, c);
  // Always-on metrics, recorded whether or not a threshold uses them (cases without a
  // reference: against the analytic image, when there is one).
  const FloatImage* ref = c.reference_spp ? &reference_for(ctx, aov, last) : (ctx.analytic ? &*ctx.analytic : nullptr);
  if (ref) {
    row.metrics["flip_vs_reference"] = compute_metric(c, "flip", final_image, ref, nullptr);
    row.metrics["psnr_vs_reference"] = compute_metric(c, "psnr", final_image, ref, nullptr);
    row.metrics["relmse_vs_reference"] = compute_metric(c, "relmse", final_image, ref, nullptr);
    // Every ROI's ratio to the path-traced reference at the last frame, so rows without an
    // accuracy bound (ablations such as probe-volume's per-mitigation rows) still record it;
    // a roi_ratio threshold below replaces the value with its worst over the evaluated frames.
    if (c.reference_spp)
      for (const Roi& roi : c.rois)
        row.metrics["roi_ratio_vs_reference_" + roi.name] = compute_metric(c, "roi_ratio", final_image, ref, &roi);
  }
  MetricSeries series{r.curve.empty() ? nullptr : &r.curve, r.last_frames.size() < 2 ? nullptr : &r.last_frames,
                      r.scanned ? &r.stability : nullptr, r.nan_pixels.empty() ? nullptr : &r.nan_pixels};
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
  auto nf = metrics::count_non_finite(r.image);
  row.metrics["nan_count"] = double(nf.nan);
  row.metrics["inf_count"] = double(nf.inf);
  std::optional<FloatImage> golden, rounded_output;  // rounded_output: the output as a half golden stores it
  bool golden_half = false;
  if (kind == "technique") {
    std::string stem = GoldenStore::technique_stem(run.name(), preset);
    std::string path = ctx.store.find(stem, ctx.golden_cls);
    if (path.empty()) {
      row.messages.push_back(fmt::format(
          "{}/{}.exr: golden missing; create it with: gibench update-goldens --case {} --technique {}{} --reason \"initial golden\"",
          ctx.store.dir(), stem, c.name, run.technique, ctx.tier == "gpu" ? " --tier gpu" : ""));
      failed = true;
    } else {
      golden = ctx.store.read(path, &golden_half);
      row.golden_class =
          fs::path(path).filename() == ctx.store.file_name(stem, ctx.golden_cls) ? ctx.golden_cls : "lavapipe";
      if (row.golden_class != ctx.golden_cls)
        row.messages.push_back(fmt::format(
            "compared with the {} golden ({}): no {} golden is approved for this run; approve one on a device of that class with: "
            "gibench update-goldens --case {} --technique {} --reason \"...\"",
            row.golden_class, fs::path(path).filename().string(), ctx.golden_cls, c.name, run.technique));
      // A half-float golden (the GPU tier's) stores the output rounded to half: compare the
      // output rounded the same way, so an unchanged technique differs in no value.
      if (golden_half) rounded_output = round_to_half(r.image);
      const FloatImage& out = golden_half ? *rounded_output : r.image;
      Threshold gt{"flip", "golden", "", c.golden_flip_max, std::nullopt};
      CheckResult cr = check_value(gt, compute_metric(c, "flip", out, &*golden, nullptr), 0);
      row.metrics["flip_vs_golden"] = cr.value;
      // Determinism (every technique is bit-identical run to run on one device and driver):
      // how many floats differ from the approved golden, and by how much at most.
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
      failed |= !cr.pass;
    }
  }
  // Variants: the same technique and preset with other options, rendered once each.
  std::map<std::string, CaseRender> variants;
  auto variant = [&](const std::string& name) -> const CaseRender& {
    auto it = variants.find(name);
    if (it != variants.end()) return it->second;
    TechniqueRun v = run;
    for (auto& [k, val] : run.variants.at(name)) v.options[k] = val;
    return variants[name] = render_case(gpu, c, v, preset);
  };
  for (auto& t : run.thresholds) {
    if (t.metric.rfind("scan_", 0) == 0 && !series.stability) {
      CheckResult skipped{t.metric, t.against, t.roi, 0, t.max, t.min, true, true,
                          fmt::format("{} skipped: the stability scan did not run (--no-stability-scan)", t.metric)};
      row.messages.push_back(skipped.message);
      row.checks.push_back(std::move(skipped));
      continue;
    }
    if (t.metric.rfind("stat_", 0) == 0) {
      // A technique's GPU counter (Technique::stats), read after the last frame.
      auto it = r.stats.find(t.metric.substr(5));
      if (it == r.stats.end())
        throw CaseError(fmt::format("{}: {} {}: metric {} is not counted in this run (its pass does not run with these options)",
                                    c.file, run.technique, preset, t.metric));
      CheckResult cr = check_value(t, it->second, 0);
      row.checks.push_back(cr);
      failed |= !cr.pass;
      continue;
    }
    if (t.against == "golden" && !golden) {  // the row has failed on the missing golden already
      CheckResult missing{t.metric, t.against, t.roi, std::numeric_limits<double>::quiet_NaN(), t.max, t.min, false, false,
                          fmt::format("{} vs golden: no approved golden to compare with", t.metric)};
      row.checks.push_back(std::move(missing));
      failed = true;
      continue;
    }
    const Roi* roi = t.roi.empty() ? nullptr : find_roi(c, t.roi);
    // Series metrics and the golden are measured once; image metrics at every evaluation frame.
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
    failed |= !worst.pass;
  }
  if (nf.nan || nf.inf) {
    row.messages.push_back(fmt::format("output has {} NaN and {} Inf values", nf.nan, nf.inf));
    failed = true;
  }
  for (auto& cr : row.checks)
    if (!cr.pass) row.messages.push_back(cr.message);
  // First offenders are reported on every row (a threshold on scan_* decides pass/fail).
  for (auto& line : row.stability.first_offender_lines()) row.messages.push_back("stability: " + line);
  save_images(ctx.o, row.image_id, final_image, ref, c);
  for (auto& [name, vr] : variants)
    save_images(ctx.o, row.image_id + ".variant-" + name, image_at(vr, last, c), ref, c);
  for (auto& [name, img] : r.views) {
    row.views.push_back({name, row.image_id + ".view-" + name});
    save_images(ctx.o, row.views.back().second, img, nullptr, c);
  }
  row.printouts = r.printouts;
  row.status = failed ? "fail" : "pass";
  if (std::string known = run.known_failure_on(ctx.cls, ctx.tier); !known.empty() && kind == "technique") {
    if (failed) {
      row.status = "known_failure";
      row.messages.insert(row.messages.begin(), "known failure: " + known);
    } else {
      row.status = "fail";
      row.messages.push_back(fmt::format(
          "marked known_failure on {} at the {} tier but every check passed: remove it from the case ({})", ctx.cls,
          ctx.tier, known));
    }
  }
  return row;
}

// The FLIP between two reference renders with different seeds (goldens.h, measure_noise_floor).
// --noise-floor measures it at the spp golden.json records for the committed reference and
// records it in golden.json (metadata only; no golden image is touched); every run rejects flip
// bounds vs the reference below 3x the recorded floor (check_noise_floor_bounds).
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

}  // namespace

int cmd_run(const SuiteOptions& o) {
  std::vector<Case> cases = select_cases(o);
  for (const std::string& t : o.techniques) find_technique(t);  // an unknown name is an error, not an empty run
  auto gpu = Gpu::create({o.device, o.validate});
  SuiteResult suite;
  suite.device = gpu->info();
  suite.device_class = device_class(suite.device.driver_name, suite.device.name);
  suite.golden_class = o.golden_class.empty() ? suite.device_class : o.golden_class;
  const Tier tier = resolve_tier(o.tier, suite.device_class);
  suite.tier = tier_name(tier);
  for (Case& c : cases) c = at_tier(c, tier);
  const std::string cache_root = tier == Tier::gpu ? reference_cache_root(o.reference_cache) : "";
  fmt::print("device: {} ({} {}), device class {}, golden class {}, tier {}{}\n", suite.device.name,
             suite.device.driver_name, suite.device.driver_info, suite.device_class, suite.golden_class, suite.tier,
             tier == Tier::gpu ? fmt::format(" (references cached in {})", cache_root) : "");
  // Sharding: row i of the plan runs in shard i % N; a case none of whose rows is ours is skipped
  // whole (no reference read).
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  const std::vector<std::string> plan = plan_rows(cases);
  std::set<std::string> ours, our_cases;
  for (size_t i = 0; i < plan.size(); ++i)
    if (i % shard.count == shard.index) {
      ours.insert(plan[i]);
      our_cases.insert(plan[i].substr(0, plan[i].find('/')));  // row keys are "case/..."
    }
  if (shard.active()) {
    suite.shard = {{"index", shard.index}, {"count", shard.count}, {"plan", plan},
                   {"rows", std::vector<std::string>(ours.begin(), ours.end())}};
    fmt::print("shard {}/{}: {} of {} rows\n", shard.index, shard.count, ours.size(), plan.size());
  }
  auto is_ours = [&](const Case& c, const std::string& kind, const std::string& technique, const std::string& preset,
                     const std::string& control) { return ours.count(row_key(c.name, kind, technique, preset, control)) > 0; };
  auto selected = [&](const std::string& technique) { return technique_selected(o.techniques, technique); };
  for (const Case& c : cases) {
    if (!our_cases.count(c.name)) continue;
    const bool any = std::any_of(c.techniques.begin(), c.techniques.end(), [&](auto& r) { return selected(r.technique); }) ||
                     std::any_of(c.negative_controls.begin(), c.negative_controls.end(),
                                 [&](auto& nc) { return selected(nc.run.technique); });
    if (!any) continue;
    // GPU tier: references come from the cache; any missing are rendered first.
    bool rendered = false;
    std::optional<ReferenceSource> src;
    try {
      src = prepare_references(*gpu, o.goldens_dir, cache_root, c, tier, &rendered);
    } catch (const std::exception& e) {
      suite.case_errors.push_back(fmt::format("{}: {}", c.name, e.what()));
      continue;
    }
    if (tier == Tier::gpu && c.reference_spp) {
      nlohmann::json meta = src->store.metadata();
      suite.references[c.name] = {{"key", src->key}, {"dir", src->store.dir()}, {"rendered", rendered},
                                  {"spp", recorded_reference_spp(c, meta)},
                                  {"noise_floor", reference_floor(c, *src)},
                                  {"target", src->request.target_floor},
                                  {"converged", references_converged(c, *src)}};
    }
    CaseContext ctx{c, technique_store(o.goldens_dir, c.name, tier), src->store, suite.tier, suite.device_class,
                    suite.golden_class, {}, {}, o};
    if (c.analytic_value) ctx.analytic = FloatImage(c.width, c.height, 4, float(*c.analytic_value));
    try {
      check_noise_floor(ctx, *gpu);
      for (auto& run : c.techniques)
        for (auto& preset : run.presets) {
          if (!is_ours(c, "technique", run.name(), preset, "") || !selected(run.technique)) continue;
          ResultRow row = evaluate(ctx, *gpu, run, preset, "technique");
          suite.rows.push_back(std::move(row));
        }
      for (auto& nc : c.negative_controls) {
        if (!is_ours(c, "negative_control", nc.run.technique, "", nc.name) || !selected(nc.run.technique)) continue;
        ResultRow row = evaluate(ctx, *gpu, nc.run, nc.run.presets.front(), "negative_control", nc.name);
        row.control_name = nc.name;
        row.control_why = nc.why;
        bool caught = std::any_of(row.checks.begin(), row.checks.end(), [](auto& cr) { return !cr.pass; });
        std::vector<std::string> skipped;
        for (auto& cr : row.checks)
          if (cr.skipped) skipped.push_back(cr.message);
        row.messages.clear();
        const std::string not_caught = nc.not_caught_reason(suite.device_class, suite.tier);
        if (!not_caught.empty()) {  // measured not to show here: an uncaught control is expected
          row.status = caught ? "fail" : "skipped";
          row.messages.push_back(caught ? fmt::format("negative control '{}' is marked not_caught_on {} at the {} tier "
                                                      "but was caught: remove the mark ({})",
                                                      nc.name, suite.device_class, suite.tier, not_caught)
                                        : fmt::format("not caught on {} at the {} tier, as the case records: {}",
                                                      suite.device_class, suite.tier, not_caught));
        } else if (!caught && !skipped.empty()) {  // what could have caught it did not run
          row.status = "skipped";
          row.messages = skipped;
        } else if (caught) {
          row.status = "pass";
          for (auto& cr : row.checks)
            if (!cr.pass) row.messages.push_back("caught as expected: " + cr.message);
        } else {
          row.status = "fail";
          row.messages.push_back(fmt::format(
              "negative control '{}' passed every threshold: the case cannot tell good from bad ({})", nc.name,
              nc.why));
        }
        suite.rows.push_back(std::move(row));
      }
    } catch (const std::exception& e) {
      suite.case_errors.push_back(fmt::format("{}: {}", c.name, e.what()));
    }
    // A reference short of its floor (a budgeted `gibench references --max-spp`) is said on every
    // row compared with it, never silently.
    if (suite.references.contains(c.name) && !suite.references[c.name]["converged"].get<bool>()) {
      const auto& r = suite.references[c.name];
      for (ResultRow& row : suite.rows)
        if (row.case_name == c.name)
          row.messages.push_back(fmt::format(
              "reference not converged: noise floor {:.4f} > {:.4f} at {} spp (refine it: gibench references --case {})",
              r["noise_floor"].get<double>(), r["target"].get<double>(), r["spp"].get<uint32_t>(), c.name));
    }
    // Report previews of the references each row links (per-frame cases: the last frame's).
    {
      uint32_t at = per_frame_references(c) ? evaluation_frames(c).back() : 0;
      for (auto& aov : compared_aovs(c)) {
        auto it = ctx.references.find(GoldenStore::reference_stem(aov, c.output, at));
        if (it != ctx.references.end())
          write_report_image((fs::path(o.out) / "img" / fmt::format("{}__reference.{}", c.name, aov)).string(),
                             it->second);
      }
    }
  }
  for (auto& m : gpu->validation_messages()) suite.case_errors.push_back("validation: " + m);
  write_suite_outputs(o.out, suite, cases);
  print_suite_table(suite);
  int fails = suite.failures();
  auto count = [&](const char* status) {
    return int(std::count_if(suite.rows.begin(), suite.rows.end(), [&](auto& r) { return r.status == status; }));
  };
  int known = count("known_failure"), skipped = count("skipped");
  fmt::print("{} passed, {} failed{}{}\n", int(suite.rows.size()) + int(suite.case_errors.size()) - fails - known - skipped,
             fails, known ? fmt::format(", {} known failures (not counted)", known) : "",
             skipped ? fmt::format(", {} negative controls skipped (their thresholds need the stability scan)", skipped) : "");
  fmt::print("report: {}\n", (fs::path(o.out) / "index.html").string());
  return fails ? 1 : 0;
}

}  // namespace gib
