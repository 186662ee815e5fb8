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
// `against`: "reference" (the path-traced golden), "golden" (this technique's approved
// golden), or "analytic" (a constant image of Case::analytic_value). Metrics measured on the
// output alone (roi_mean, nan_count, inf_count) take no `against`: the loader leaves it "".
struct Threshold {
  std::string metric;
  std::string against = "reference";
  std::string roi;                   // "" = whole image
  std::optional<double> max, min;    // at least one
};

// A technique run: technique x presets, with named options (technique settings, e.g.
// "sky_rays": 0 or "max_bounces": 1) and thresholds. Each preset is one result row.
struct TechniqueRun {
  std::string technique;
  std::vector<std::string> presets;         // default {"medium"}
  std::map<std::string, double> options;    // validated against the technique's option names
  std::string compare_aov;                  // reference AOV this output is compared to ("" = Case::output)
  std::vector<Threshold> thresholds;
};

// A configuration that must FAIL at least one of its thresholds; if it passes, the case fails
// (it proves the case can tell good from bad).
struct NegativeControl {
  std::string name;
  std::string why;  // what it breaks, in words
  TechniqueRun run; // presets: exactly one
};

struct Case {
  std::string name;         // file stem, e.g. "cornell"
  std::string file;         // path it was loaded from
  std::string description;
  Scene scene;              // inline, or loaded from "scene": "scenes/cornell.json" (relative to the case file)
  std::string scene_file;   // "" when inline
  uint32_t width = 256, height = 144;
  uint32_t frames = 1;      // frames rendered for non-reference techniques (the last is compared)
  std::string output = "radiance";  // reference AOV compared by default
  uint32_t reference_spp = 256;
  uint32_t reference_seed = 1;
  std::optional<double> analytic_value;  // for against == "analytic"
  std::string flip_mode = "hdr";         // "hdr" or "ldr"
  double ppd = 67.02064514160156;        // FLIP pixels per degree (the reference tool's default)
  double golden_flip_max = 0.01;         // regression threshold vs the approved golden
  std::vector<Roi> rois;
  std::vector<TechniqueRun> techniques;
  std::vector<NegativeControl> negative_controls;
};

// The metric names a Threshold may use, in the order documented above.
const std::vector<std::string>& case_metrics();
// False for the metrics measured on the output alone (roi_mean, nan_count, inf_count).
bool metric_uses_against(const std::string& metric);

Case load_case(const std::string& path);
// Every cases/*.json (not recursive, sorted by file name; *.schema.json skipped); throws
// CaseError on the first bad file, or when `dir` is not a directory or holds no case.
std::vector<Case> load_cases(const std::string& dir);

}  // namespace gib
