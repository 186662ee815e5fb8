// Rendering one case x technique x preset (x options) on a Gpu: shared by run,
// update-goldens, the noise floor and sweep.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "harness/case.h"
#include "harness/render.h"

namespace gib {

struct CaseRender {
  std::string technique, preset;
  FloatImage image;                  // the compared output (technique output, or a reference AOV)
  std::map<std::string, FloatImage> aovs;  // reference: every AOV
  std::vector<PassStats> passes;
  Plan plan;
  double frame_median_ms = 0;
  double gpu_ms_total = 0;           // sum over frames (reference: the whole convergence)
  uint32_t frames = 0, spp = 0;
  std::string settings_hash;
};

// `aov` picks the reference AOV compared ("" = the case's output). Reference runs use the
// case's reference_spp and seed (seed_offset shifts it: the noise floor renders twice).
CaseRender render_case(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                       uint32_t seed_offset = 0);

}  // namespace gib
