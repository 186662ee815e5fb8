// Scenario cases: a JSON file in cases/ (schema: cases/case.schema.json) describing a scene,
// what to render with which techniques and presets, what to compare it against, thresholds,
// expectations and negative controls. load_case() validates everything up front; errors are
// CaseError with one line: "<file>: <json pointer>: expected <what>, got <what>".
#pragma once
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace gib {

struct CaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The value a map keyed by device class and tier (known_failure, not_caught_on) gives on
// `device_class` at `tier`: the first of the keys CLASS@TIER, *@TIER, CLASS, * present ("" if none).
inline std::string device_keyed(const std::map<std::string, std::string>& m, const std::string& device_class,
                                const std::string& tier) {
  for (const std::string& k : {device_class + "@" + tier, "*@" + tier, device_class, std::string("*")})
    if (auto it = m.find(k); it != m.end()) return it->second;
  return "";
}

// A rectangle in normalised image coordinates ([0,1]^2, origin top-left), so a case works
// at any render size.
struct Roi {
  std::string name;
  float x0 = 0, y0 = 0, x1 = 1, y1 = 1;
};

// One metric checked against a bound. `metric` names one the runner computes:
//   flip                      mean LDR/HDR-FLIP (mode from Case::flip_mode) vs `against`
//   psnr                      dB on tone-mapped sRGB [0,1] vs `against`
//   relmse                    relative MSE on linear HDR vs `against`
//   roi_mean                  mean luminance in `roi` of the output (no `against`)
//   roi_ratio                 roi_mean(output) / roi_mean(against)
//   max_abs_error             largest |output - against| over channels and pixels
//   nan_count, inf_count      non-finite values in the output
//   uv_shift_max              largest CIE 1976 u'v' distance per pixel vs `against` (pixels
//                             darker than 1e-3 skipped; metrics::chromaticity_shift)
//   banding                   banding index of the output's luminance (metrics::banding_index)
//   banding_excess            banding(output) - banding(against): the part the content lacks
//   penumbra_width_error      |w(output) - w(against)| / w(against): 10-90 % penumbra width along
//                             x of the ROI's mean row profile, levels from against's (needs roi)
//   flicker                   mean per-pixel relative std of luminance over the last
//                             Case::flicker_frames frames (needs flicker_frames)
//   conv_error_final          |m - t| / t at the last frame, m = ROI mean luminance per frame,
//                             t = Case::convergence target (needs convergence)
//   conv_error_max            max |m - t| / t over frames >= convergence.settle_frame
//   conv_drift                |mean m over the last 10% of frames - mean over the first 10%
//                             from settle_frame| / t: slow drift after convergence
//   conv_oscillation          (total variation of m from settle_frame on - |net change|) / t,
//                             after a 5-frame moving mean: 0 for a monotone approach
//   nan_frames                frames whose output had a NaN pixel (needs track_nan)
//   nan_last_frame            the last such frame (1-based; 0: none)
//   nan_max_pixels            the most NaN pixels in any one frame's output
//   scan_nan, scan_inf,       offending texels/elements over every frame, pass and resource of
//   scan_negative,            the GPU stability scan (renderer/graph/stability.h; needs the
//   scan_above_max,           scan on, the default of `gibench run`); scan_saturated: |value|
//   scan_saturated            at the storage format's largest finite value (silent clamp)
// `against`: "reference" (the path-traced golden), "golden" (this technique's approved
// golden), "analytic" (a constant image of Case::analytic_value) or "variant:NAME" (the same
// technique and preset rendered with TechniqueRun::variants[NAME] on top of its options).
// Metrics measured on the output alone take no `against`: the loader leaves it "".
struct Threshold {
  std::string metric;
  std::string against = "reference";
  std::string roi;                   // "" = whole image
  std::optional<double> max, min;    // at least one
  uint32_t frame = 0;                // one of Case::eval_frames; 0 = every evaluation frame
};

// A technique run: technique x presets, with named options (technique settings, e.g.
// "sky_rays": 0 or "max_bounces": 1) and thresholds. Each preset is one result row.
struct TechniqueRun {
  std::string technique;
  // Optional: tells apart runs of one technique and preset with other options (alpha-foliage's
  // strategies). The row, its images and its golden are named name() = technique+label.
  std::string label;
  std::string name() const { return label.empty() ? technique : technique + "+" + label; }
  std::vector<std::string> presets;         // default {"medium"}
  std::map<std::string, double> options;    // validated against the technique's option names
  std::string compare_aov;                  // reference AOV this output is compared to ("" = Case::output)
  std::vector<Threshold> thresholds;
  bool attribute = false;  // error attribution of this row under `gibench run --attribute`
  // Named option sets rendered alongside (same technique and preset; these options on top of
  // `options`) as comparison images: a threshold's against "variant:NAME".
  std::map<std::string, std::map<std::string, double>> variants;
  // Non-empty: a defect known to make this run fail, in words (with the issue or note that
  // tracks it). A failing run is reported as "known_failure" and does not fail the suite; a
  // run that passes fails it ("remove known_failure"), so the mark cannot go stale. Keyed by
  // device class (harness/goldens.h device_class), "*" for every class: a defect may show on
  // one class of device only (a precision-dependent leak, a driver's rounding); CLASS@TIER and
  // *@TIER (ci, gpu) for one tier only.
  std::map<std::string, std::string> known_failure;
  // The known failure that applies on `device_class` at `tier` ("" if none): the first of the
  // keys CLASS@TIER, *@TIER, CLASS, * present.
  std::string known_failure_on(const std::string& device_class, const std::string& tier = "ci") const {
    return device_keyed(known_failure, device_class, tier);
  }
  // A reference (path tracer) row's samples per pixel, split over frames like a committed
  // reference's; independent of Case::reference_spp (the committed reference's budget, often
  // 65536+ and rendered on a GPU). 0: the case's frames at the preset's spp per frame.
  uint32_t spp = 0;
  // > 0: frames this run renders instead of the case's (a technique that converges over many
  // frames beside rows that need few, e.g. probe-volume in alpha-foliage); its last frame is
  // compared. Not for reference runs (they have spp) nor in cases evaluated per frame
  // (eval_frames, convergence, flicker_frames).
  uint32_t frames = 0;
};

// Per-frame tracking of the mean luminance in one ROI (the convergence curve): conv_* metrics.
struct Convergence {
  std::string roi;            // "" = whole image
  double target = 1.0;        // the value m should converge to (default: analytic_value)
  uint32_t settle_frame = 1;  // frames before this one (1-based) are the approach, not checked
};

// A configuration that must FAIL at least one of its thresholds; if it passes, the case fails
// (it proves the case can tell good from bad).
struct NegativeControl {
  std::string name;
  std::string why;  // what it breaks, in words
  TechniqueRun run; // presets: exactly one
  // Device classes / tiers (known_failure's keys) where the break is measured not to show, with
  // the measurement in words: there an uncaught control is reported "skipped" with the words
  // instead of failing the suite, and a caught one fails ("remove not_caught_on"), so the mark
  // cannot go stale.
  std::map<std::string, std::string> not_caught_on;
  std::string not_caught_reason(const std::string& device_class, const std::string& tier) const {
    return device_keyed(not_caught_on, device_class, tier);
  }
};

struct Case {
  std::string name;         // file stem, e.g. "cornell"
  std::string file;         // path it was loaded from
  std::string description;
  Scene scene;              // inline, or loaded from "scene": "scenes/cornell.json" (relative to the case file)
  std::string scene_file;   // "" when inline
  // What the scene was read from: the scene file's bytes, or the inline scene's JSON (the GPU
  // tier's reference cache key, harness/references.h).
  std::string scene_text;
  // The CI tier's size (lavapipe, CI: small), and the GPU tier's (harness/tier.h: chosen on GPU
  // devices; 640x360 by default, the size Falcor's image tests use).
  uint32_t width = 256, height = 144;
  uint32_t gpu_width = 640, gpu_height = 360;
  uint32_t frames = 1;      // frames rendered for non-reference techniques (the last is compared)
  // 1-based frames at which thresholds are evaluated (the worst value counts); empty = the
  // last frame. In a scene with motion, each has its own reference rendered at that frame's
  // time (goldens reference.<aov>.f<N>.exr).
  std::vector<uint32_t> eval_frames;
  std::optional<Convergence> convergence;  // record the ROI mean every frame
  uint32_t flicker_frames = 0;             // >= 2: keep the last N outputs for the flicker metric
  bool track_nan = false;                  // count NaN pixels of the output every frame (nan_* metrics)
  // Frames rendered after the case's frames and every read, with the stability scan off, from
  // which GPU times are taken (perf/frame_timing.h; 0: the case's own frames are timed).
  uint32_t timing_frames = 8;
  std::string output = "radiance";  // reference AOV compared by default
  uint32_t reference_spp = 256;      // 0: no path-traced reference (analytic cases only)
  uint32_t reference_seed = 1;
  std::optional<double> analytic_value;  // for against == "analytic"
  std::string flip_mode = "hdr";         // "hdr" or "ldr"
  double ppd = 67.02064514160156;        // FLIP pixels per degree (the reference tool's default)
  double golden_flip_max = 0.001;        // regression threshold vs the approved golden
  std::vector<Roi> rois;
  std::vector<TechniqueRun> techniques;
  std::vector<NegativeControl> negative_controls;
};

// The reference AOVs the case's runs and negative controls compare with, the output first, each once.
std::vector<std::string> compared_aovs(const Case& c);

// The metric names a Threshold may use, in the order documented above.
const std::vector<std::string>& case_metrics();
// False for the metrics measured on the output alone (roi_mean, nan_count, inf_count).
bool metric_uses_against(const std::string& metric);

Case load_case(const std::string& path);
// Every cases/*.json (not recursive, sorted by file name; *.schema.json skipped); throws
// CaseError on the first bad file, or when `dir` is not a directory or holds no case.
std::vector<Case> load_cases(const std::string& dir);

}  // namespace gib
