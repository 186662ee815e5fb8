#include "harness/case_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <nlohmann/json.hpp>

#include "harness/goldens.h"
#include "metrics/image_metrics.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"

namespace gib {

std::vector<uint32_t> evaluation_frames(const Case& c) {
  return c.eval_frames.empty() ? std::vector<uint32_t>{c.frames} : c.eval_frames;
}

bool per_frame_references(const Case& c) {
  return !c.eval_frames.empty() && c.scene.features().has(Feature::motion);
}

CaseRender render_case(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                       uint32_t seed_offset, uint32_t at_frame, bool scan) {
  const Technique& t = find_technique(run.technique);
  Settings s;
  s.width = c.width;
  s.height = c.height;
  s.seed = c.reference_seed + seed_offset;
  s = apply_preset(t, preset, s);
  const bool reference = t.name == "reference";
  uint32_t frames = c.frames;
  // With reference_spp 0 (no reference image: analytic or variant-only cases) a reference row
  // runs the case's frames at its preset's (or options') samples per frame, like any technique.
  const bool spp_budget = reference && c.reference_spp > 0;
  if (spp_budget) {
    uint32_t& spp = s.params<ReferenceSettings>().spp_per_frame;
    spp = std::min<uint32_t>(c.reference_spp, 16);
    while (c.reference_spp % spp) --spp;
  }
  s = apply_options(t, s, run.options);
  if (spp_budget) frames = std::max(1u, c.reference_spp / s.params<ReferenceSettings>().spp_per_frame);
  if (reference) {
    // A reference never moves while it converges: it shows one moment of the scene.
    s.scene_time = float(at_frame ? at_frame - 1 : 0) * c.scene.frame_time;
  }

  std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  // A technique that produces the compared AOV itself (e.g. radiance-cache's indirect_diffuse)
  // is compared on that AOV; otherwise on its final output.
  bool own_aov = std::find(t.aovs.begin(), t.aovs.end(), aov) != t.aovs.end();
  std::string out_name = reference ? aov : (own_aov ? aov : t.output);
  std::vector<std::string> outputs{out_name};
  if (reference)
    for (auto& a : std::vector<std::string>{t.output, "direct", "indirect_diffuse"})
      if (std::find(outputs.begin(), outputs.end(), a) == outputs.end()) outputs.push_back(a);

  Executor ex(gpu, c.scene, s, make_passes(t), outputs);
  ex.enable_stability_scan(scan);
  std::vector<FrameResult> results;
  CaseRender r;
  std::vector<uint32_t> eval = reference ? std::vector<uint32_t>{} : evaluation_frames(c);
  std::optional<metrics::Roi> curve_roi;
  // A reference accumulating to its spp budget draws no curve; one running frames (see above) does.
  if (!spp_budget && c.convergence) {
    curve_roi = metrics::Roi{};
    for (auto& roi : c.rois)
      if (roi.name == c.convergence->roi) curve_roi = metrics::Roi{roi.x0, roi.y0, roi.x1, roi.y1};
  }
  const uint32_t keep_last = spp_budget ? 0 : c.flicker_frames;
  for (uint32_t f = 1; f <= frames; ++f) {
    results.push_back(ex.run_frame());
    bool eval_here = std::find(eval.begin(), eval.end(), f) != eval.end();
    bool keep = keep_last && f + keep_last > frames;
    const bool track_nan = c.track_nan;  // the reference too: its accumulation is temporal
    if (!eval_here && !keep && !curve_roi && !track_nan) continue;
    FloatImage img = ex.read(out_name);
    if (track_nan) {
      size_t n = 0;
      for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
          bool bad = false;
          for (uint32_t ch = 0; ch < img.channels; ++ch) bad |= std::isnan(img.at(x, y, ch));
          n += bad;
        }
      r.nan_pixels.push_back(double(n));
    }
    if (curve_roi) r.curve.push_back(metrics::roi_mean_luminance(img, *curve_roi));
    if (keep) r.last_frames.push_back(img);
    if (eval_here) r.frame_images[f] = std::move(img);
  }
  r.technique = t.name;
  r.preset = preset;
  r.plan = ex.plan();
  r.passes = summarize(results);
  std::vector<double> totals;
  for (auto& fr : results) {
    totals.push_back(fr.total_ms);
    r.gpu_ms_total += fr.total_ms;
  }
  std::sort(totals.begin(), totals.end());
  r.frame_median_ms = totals.empty() ? 0 : totals[totals.size() / 2];
  r.frames = frames;
  r.spp = reference ? frames * s.params<ReferenceSettings>().spp_per_frame : 0;
  r.image = ex.read(out_name);
  r.scanned = scan;
  if (scan) r.stability = ex.stability();
  if (reference)
    for (auto& a : outputs) r.aovs[a] = a == out_name ? r.image : ex.read(a);
  nlohmann::json key{{"case", c.name}, {"technique", t.name}, {"preset", preset}, {"options", run.options},
                     {"size", {c.width, c.height}}, {"frames", frames}, {"seed", s.seed},
                     {"spp", r.spp}, {"scene", c.scene_file.empty() ? std::string("inline") : c.scene_file}};
  if (at_frame) key["at_frame"] = at_frame;
  r.settings_hash = fnv1a_hex(key.dump());
  return r;
}

}  // namespace gib
