#include "harness/runner.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fnmatch.h>
#include <set>

#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/image_io.h"
#include "harness/metrics/flip.h"
#include "harness/metrics/image_metrics.h"
#include "harness/report.h"
#include "renderer/techniques/technique.h"

namespace fs = std::filesystem;

namespace gib {

int SuiteResult::failures() const {
  int n = static_cast<int>(case_errors.size());
  for (auto& r : rows) n += r.status != "pass";
  return n;
}

bool glob_match(const std::string& pattern, const std::string& text) {
  return fnmatch(pattern.c_str(), text.c_str(), 0) == 0;
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

}  // namespace

double compute_metric(const Case& c, const std::string& metric, const FloatImage& output, const FloatImage* against,
                      const Roi* roi) {
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
  if (metric == "nan_count") return double(metrics::count_non_finite(crop(output, roi)).nan);
  if (metric == "inf_count") return double(metrics::count_non_finite(crop(output, roi)).inf);
  throw CaseError(fmt::format("{}: unknown metric '{}'", c.file, metric));
}

namespace {

struct CaseContext {
  const Case& c;
  GoldenStore store;
  std::string cls;
  std::map<std::string, FloatImage> references;  // by AOV
  std::optional<FloatImage> analytic;
  const SuiteOptions& o;
};

const FloatImage& reference_for(CaseContext& ctx, const std::string& aov) {
  auto it = ctx.references.find(aov);
  if (it != ctx.references.end()) return it->second;
  std::string stem = GoldenStore::reference_stem(aov, ctx.c.output);
  std::string path = ctx.store.find(stem, ctx.cls);
  if (path.empty())
    throw GoldenError(fmt::format(
        "{}/{}.exr: golden missing; create it with: gibench update-goldens --case {} --reference --reason \"initial reference\"",
        ctx.store.dir(), stem, ctx.c.name));
  return ctx.references[aov] = ctx.store.read(path);
}

const FloatImage* against_image(CaseContext& ctx, const std::string& against, const std::string& aov,
                                const FloatImage* golden) {
  if (against == "reference") return &reference_for(ctx, aov);
  if (against == "golden") return golden;
  if (against == "analytic") return ctx.analytic ? &*ctx.analytic : nullptr;
  return nullptr;
}

CheckResult check(CaseContext& ctx, const Threshold& t, const FloatImage& out, const FloatImage* against) {
  CheckResult r;
  r.metric = t.metric;
  r.against = t.against;
  r.roi = t.roi;
  r.max = t.max;
  r.min = t.min;
  const Roi* roi = t.roi.empty() ? nullptr : find_roi(ctx.c, t.roi);
  r.value = compute_metric(ctx.c, t.metric, out, against, roi);
  std::string what = fmt::format("{} vs {}{}", t.metric, t.against, t.roi.empty() ? "" : " in " + t.roi);
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

ResultRow evaluate(CaseContext& ctx, Gpu& gpu, const TechniqueRun& run, const std::string& preset,
                   const std::string& kind) {
  ResultRow row;
  row.case_name = ctx.c.name;
  row.technique = run.technique;
  row.preset = preset;
  row.kind = kind;
  row.options = run.options;
  row.device = gpu.info().name;
  std::string aov = run.compare_aov.empty() ? ctx.c.output : run.compare_aov;
  CaseRender r = render_case(gpu, ctx.c, run, preset);
  row.gpu_ms = r.frame_median_ms;
  row.passes = r.passes;
  row.plan = r.plan;
  row.image_id = fmt::format("{}__{}.{}{}", ctx.c.name, run.technique, preset,
                             kind == "negative_control" ? ".negative" : "");
  row.reference_id = fmt::format("{}__reference.{}", ctx.c.name, aov);
  bool failed = false;
  const FloatImage& ref = reference_for(ctx, aov);
  // Always-on metrics, recorded whether or not a threshold uses them.
  row.metrics["flip_vs_reference"] = compute_metric(ctx.c, "flip", r.image, &ref, nullptr);
  row.metrics["psnr_vs_reference"] = compute_metric(ctx.c, "psnr", r.image, &ref, nullptr);
  row.metrics["relmse_vs_reference"] = compute_metric(ctx.c, "relmse", r.image, &ref, nullptr);
  auto nf = metrics::count_non_finite(r.image);
  row.metrics["nan_count"] = double(nf.nan);
  row.metrics["inf_count"] = double(nf.inf);
  std::optional<FloatImage> golden;
  if (kind == "technique") {
    std::string stem = GoldenStore::technique_stem(run.technique, preset);
    std::string path = ctx.store.find(stem, ctx.cls);
    if (path.empty()) {
      row.messages.push_back(fmt::format(
          "{}/{}.exr: golden missing; create it with: gibench update-goldens --case {} --technique {} --reason \"initial golden\"",
          ctx.store.dir(), stem, ctx.c.name, run.technique));
      failed = true;
    } else {
      golden = ctx.store.read(path);
      Threshold gt{"flip", "golden", "", ctx.c.golden_flip_max, std::nullopt};
      CheckResult cr = check(ctx, gt, r.image, &*golden);
      row.metrics["flip_vs_golden"] = cr.value;
      row.checks.push_back(cr);
      failed |= !cr.pass;
    }
  }
  for (auto& t : run.thresholds) {
    CheckResult cr = check(ctx, t, r.image, against_image(ctx, t.against, aov, golden ? &*golden : nullptr));
    std::string key = t.metric + "_vs_" + t.against + (t.roi.empty() ? "" : "_" + t.roi);
    row.metrics[key] = cr.value;
    row.checks.push_back(cr);
    failed |= !cr.pass;
  }
  if (nf.nan || nf.inf) {
    row.messages.push_back(fmt::format("output has {} NaN and {} Inf values", nf.nan, nf.inf));
    failed = true;
  }
  for (auto& cr : row.checks)
    if (!cr.pass) row.messages.push_back(cr.message);
  save_images(ctx.o, row.image_id, r.image, &ref, ctx.c);
  row.status = failed ? "fail" : "pass";
  return row;
}

// The FLIP between two reference renders with different seeds: no threshold on FLIP vs the
// reference can be tighter than this. --noise-floor measures it and records it in golden.json
// (metadata only; no golden image is touched); every run checks thresholds against it.
void check_noise_floor(CaseContext& ctx, Gpu& gpu) {
  const Case& c = ctx.c;
  nlohmann::json meta = ctx.store.metadata();
  if (ctx.o.noise_floor) {
    TechniqueRun ref_run{"reference", {"ultra"}, {}, "", {}};
    CaseRender a = render_case(gpu, c, ref_run, "ultra"), b = render_case(gpu, c, ref_run, "ultra", 1000);
    double floor = flip(a.image, b.image, flip_options(c)).mean;
    meta["noise_floor"] = {{"flip", floor}, {"spp", a.spp}, {"seeds", {c.reference_seed, c.reference_seed + 1000}},
                           {"device_class", ctx.cls}, {"date", utc_now_iso()}};
    ctx.store.write_metadata(meta);
    fmt::print("{}: noise floor (FLIP between two seeds at {} spp) {:.6f}\n", c.name, a.spp, floor);
  }
  if (!meta.contains("noise_floor")) return;
  double floor = meta["noise_floor"].value("flip", 0.0);
  for (auto& run : c.techniques)
    for (auto& t : run.thresholds)
      if (t.metric == "flip" && t.against == "reference" && t.roi.empty() && t.max && *t.max < floor)
        throw CaseError(fmt::format("{}: {} flip vs reference max {} is below the measured noise floor {:.6f} "
                                    "(golden.json): the threshold cannot be met reliably",
                                    c.file, run.technique, *t.max, floor));
}

}  // namespace

int cmd_run(const SuiteOptions& o) {
  std::vector<Case> cases = select_cases(o);
  auto gpu = Gpu::create({o.device, o.validate});
  SuiteResult suite;
  suite.device = gpu->info();
  suite.device_class = device_class(suite.device.driver_name, suite.device.name);
  fmt::print("device: {} ({} {}), golden class {}\n", suite.device.name, suite.device.driver_name,
             suite.device.driver_info, suite.device_class);
  for (const Case& c : cases) {
    CaseContext ctx{c, GoldenStore(o.goldens_dir, c.name), suite.device_class, {}, {}, o};
    if (c.analytic_value) ctx.analytic = FloatImage(c.width, c.height, 4, float(*c.analytic_value));
    try {
      check_noise_floor(ctx, *gpu);
      for (auto& run : c.techniques)
        for (auto& preset : run.presets) {
          ResultRow row = evaluate(ctx, *gpu, run, preset, "technique");
          suite.rows.push_back(std::move(row));
        }
      for (auto& nc : c.negative_controls) {
        ResultRow row = evaluate(ctx, *gpu, nc.run, nc.run.presets.front(), "negative_control");
        row.control_name = nc.name;
        row.control_why = nc.why;
        bool caught = std::any_of(row.checks.begin(), row.checks.end(), [](auto& cr) { return !cr.pass; });
        row.messages.clear();
        if (caught) {
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
    for (auto& [aov, img] : ctx.references)
      write_report_image((fs::path(o.out) / "img" / fmt::format("{}__reference.{}", c.name, aov)).string(), img);
  }
  for (auto& m : gpu->validation_messages()) suite.case_errors.push_back("validation: " + m);
  write_suite_outputs(o.out, suite, cases);
  print_suite_table(suite);
  int fails = suite.failures();
  fmt::print("{} passed, {} failed\n", int(suite.rows.size()) + int(suite.case_errors.size()) - fails, fails);
  fmt::print("report: {}\n", (fs::path(o.out) / "index.html").string());
  return fails ? 1 : 0;
}

}  // namespace gib
