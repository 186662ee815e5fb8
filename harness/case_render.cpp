#include "harness/case_render.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

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

const FloatImage& image_at(const CaseRender& r, uint32_t f, const Case& c) {
  if (f == c.frames) return r.image;
  auto it = r.frame_images.find(f);
  if (it == r.frame_images.end()) throw CaseError(fmt::format("{}: frame {} was not captured", c.file, f));
  return it->second;
}

bool per_frame_references(const Case& c) {
  return !c.eval_frames.empty() && c.scene.time_varying();
}

namespace {
uint32_t g_frames_per_submission = 64;
}  // namespace

void set_frames_per_submission(uint32_t n) { g_frames_per_submission = std::max(1u, n); }

namespace {

// `budget`: a path tracer's samples per pixel, split over frames (0: the case's frames at the
// preset's samples per frame, like any technique).
CaseRender render(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset, uint32_t seed_offset,
                  uint32_t at_frame, bool scan, uint32_t budget, const FrameProgress& progress = {},
                  const RunHooks* hooks = nullptr) {
  const Technique& t = find_technique(run.technique);
  Settings s;
  s.width = c.width;
  s.height = c.height;
  s.seed = c.reference_seed + seed_offset;
  s = apply_preset(t, preset, s);
  const bool reference = t.name == "reference";
  uint32_t frames = run.frames ? run.frames : c.frames;
  const bool spp_budget = reference && budget > 0;
  if (spp_budget) {
    // Up to 512 spp at most 16 per frame (the committed lavapipe references were split so).
    // Larger budgets (GPU references): about sqrt(budget) per frame, 16 to 256 (65536 spp =
    // 256 x 256 frames), so per-frame overhead does not dominate. Samples are numbered across
    // frames (sample_base), so the split changes only the order of the float sums.
    const uint32_t cap = budget <= 512 ? 16 : std::clamp<uint32_t>(uint32_t(std::sqrt(double(budget))), 16, 256);
    uint32_t& spp = s.params<ReferenceSettings>().spp_per_frame;
    spp = std::min<uint32_t>(budget, cap);
    while (budget % spp) --spp;
  }
  s = apply_options(t, s, run.options);
  if (spp_budget) frames = std::max(1u, budget / s.params<ReferenceSettings>().spp_per_frame);
  if (reference) {
    // A reference never moves while it converges: it shows one moment of the scene.
    s.scene_time = float(at_frame ? at_frame - 1 : 0) * c.scene.frame_time;
  } else if (hooks && hooks->frozen_frame) {
    s.scene_time = float(hooks->frozen_frame - 1) * c.scene.frame_time;
  }

  // The compared AOV, by the contract (renderer/techniques/aov.h): the resource the technique
  // declares for it. The case loader has checked that every run's technique declares it.
  std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  std::string out_name = contract_resource(t, aov);
  if (out_name.empty())
    throw std::runtime_error(fmt::format("{}: technique '{}' does not produce the AOV '{}' (it declares: {})", c.name,
                                         t.name, aov, fmt::join(contract_aov_names(t), ", ")));
  std::vector<std::string> outputs{out_name};
  if (reference)
    for (auto& a : contract_aov_names(t, c.scene.features()))
      if (std::find(outputs.begin(), outputs.end(), contract_resource(t, a)) == outputs.end())
        outputs.push_back(contract_resource(t, a));

  Executor ex(gpu, c.scene, s, make_passes(t), outputs);
  ex.enable_stability_scan(scan);
  if (hooks)
    for (const ResourceOverride& o : hooks->overrides) ex.add_override(o);
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
  const bool track_nan = c.track_nan;  // the reference too: its accumulation is temporal
  auto hook_read_after = [&](uint32_t f) {
    return hooks && !hooks->read.empty() && f < frames && f + hooks->read_frames > frames;
  };
  auto eval_after = [&](uint32_t f) { return std::find(eval.begin(), eval.end(), f) != eval.end(); };
  auto keep_after = [&](uint32_t f) { return keep_last && f + keep_last > frames; };
  // Frames after which the host reads something end a submission (Executor::run_frames); the
  // others are submitted together, up to g_frames_per_submission at a time.
  auto host_reads_after = [&](uint32_t f) {
    return hook_read_after(f) || eval_after(f) || keep_after(f) || curve_roi || track_nan;
  };
  for (uint32_t done = 0; done < frames;) {
    uint32_t n = 1;
    while (done + n < frames && n < g_frames_per_submission && !host_reads_after(done + n)) ++n;
    for (FrameResult& fr : ex.run_frames(n)) results.push_back(std::move(fr));
    if (progress)
      for (uint32_t k = 1; k <= n; ++k) progress(done + k, frames);
    done += n;
    const uint32_t f = done;  // the frame just run (1-based)
    if (hook_read_after(f)) {
      auto& reads = r.read_before.emplace_back();
      for (const std::string& name : hooks->read) reads[name] = ex.read_bytes(name);
    }
    const bool eval_here = eval_after(f), keep = keep_after(f);
    if (!eval_here && !keep && !curve_roi && !track_nan) continue;
    FloatImage img = ex.read(out_name);
    if (track_nan) {
      size_t bad_pixels = 0;
      for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
          bool bad = false;
          for (uint32_t ch = 0; ch < img.channels; ++ch) bad |= std::isnan(img.at(x, y, ch));
          bad_pixels += bad;
        }
      r.nan_pixels.push_back(double(bad_pixels));
    }
    if (curve_roi) r.curve.push_back(metrics::roi_mean_luminance(img, *curve_roi));
    if (keep) r.last_frames.push_back(img);
    if (eval_here) r.frame_images[f] = std::move(img);
  }
  r.technique = t.name;
  r.preset = preset;
  r.plan = ex.plan();
  r.texture_bytes = ex.texture_bytes();
  r.settings = ex.settings();
  r.outputs = outputs;
  for (auto& fr : results) r.gpu_ms_total += fr.total_ms;
  r.frames = frames;
  r.spp = reference ? frames * s.params<ReferenceSettings>().spp_per_frame : 0;
  r.image = ex.read(out_name);
  for (const TechniqueStat& st : t.stats) {
    if (!ex.plan().find(st.resource)) continue;
    std::vector<uint8_t> raw = ex.read_buffer(st.resource);
    const double v = buffer_word(raw, st.word), of = st.of_word == UINT32_MAX ? 0.0 : buffer_word(raw, st.of_word);
    r.stats[st.name] = st.of_word == UINT32_MAX ? v : (of > 0 ? v / of : 0.0);
  }
  for (const TechniqueView& v : t.views)
    if (ex.plan().find(v.resource)) r.views[v.name] = v.draw(ex.read_buffer(v.resource), s.width, s.height);
  for (const TechniquePrintout& p : t.printouts)
    if (ex.plan().find(p.resource)) r.printouts[p.name] = p.print(ex.read_buffer(p.resource), s.width, s.height);
  if (hooks)
    for (const std::string& name : hooks->read) r.read[name] = ex.read_bytes(name);
  r.scanned = scan;
  if (scan) r.stability = ex.stability();
  if (reference)
    for (auto& a : contract_aov_names(t, c.scene.features())) {
      std::string res = contract_resource(t, a);
      r.aovs[a] = res == out_name ? r.image : ex.read(res);
    }
  // GPU times (perf/frame_timing.h). Every image, curve and scan result was read above, so the
  // timing frames cannot change anything evaluated; they run with the scan off, the case's
  // frames serving as warm-up. With timing_frames 0, and for a reference with an spp budget
  // rendered without the scan (sweep, update-goldens, the noise floor: its convergence frames
  // are scan-free, and their sum is the cost sweep reports), the case's frames after the first
  // are timed instead; scan-free only when the scan was off (timing.scan_free says).
  const uint32_t timing_frames = (spp_budget && !scan) || hooks ? 0 : c.timing_frames;
  if (timing_frames) {
    r.timing = perf::time_frames(ex, 0, timing_frames);
  } else {
    const size_t skip = results.size() > 1 ? 1 : 0;
    r.timing = perf::timing_of({results.begin() + long(skip), results.end()}, uint32_t(skip), "case frames");
  }
  r.passes = summarize(r.timing.frames);
  r.frame_median_ms = r.timing.frame().median;
  nlohmann::json key{{"case", c.name}, {"technique", t.name}, {"preset", preset}, {"options", run.options},
                     {"size", {c.width, c.height}}, {"frames", frames}, {"seed", s.seed},
                     {"spp", r.spp}, {"scene", c.scene_file.empty() ? std::string("inline") : c.scene_file}};
  if (at_frame) key["at_frame"] = at_frame;
  if (hooks && hooks->frozen_frame) key["frozen_frame"] = hooks->frozen_frame;
  r.settings_hash = fnv1a_hex(key.dump());
  return r;
}

}  // namespace

CaseRender render_case(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                       uint32_t seed_offset, uint32_t at_frame, bool scan, const FrameProgress& progress) {
  return render(gpu, c, run, preset, seed_offset, at_frame, scan, run.technique == "reference" ? run.spp : 0, progress);
}

CaseRender render_case_hooked(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                              uint32_t seed_offset, const RunHooks& hooks) {
  return render(gpu, c, run, preset, seed_offset, 0, false, run.technique == "reference" ? run.spp : 0, {}, &hooks);
}

CaseRender render_reference(Gpu& gpu, const Case& c, uint32_t seed_offset, uint32_t at_frame,
                            const FrameProgress& progress) {
  if (c.reference_spp == 0) throw std::runtime_error(fmt::format("{}: the case has no reference (reference_spp 0)", c.name));
  TechniqueRun ref_run;
  ref_run.technique = "reference";
  ref_run.presets = {"ultra"};
  return render(gpu, c, ref_run, "ultra", seed_offset, at_frame, false, c.reference_spp, progress);
}

}  // namespace gib
