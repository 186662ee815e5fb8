// `gibench attribute --case C --technique T [--preset P] [--seeds K]`: error attribution of one
// case row (attribution.h) with the technique's stages and oracles (Technique::stages): renders
// every subset of oracles x seeds, prints a table per ROI and writes
// OUT/attribution/<case>.<row>.<preset>.json and a waterfall page (.html) beside it.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/case.h"
#include "harness/suite.h"
#include "harness/tier.h"
#include "renderer/vk/gpu.h"

namespace gib {

// How an attribution is estimated (`gibench attribute`, and `gibench run --attribute` for the
// rows a case flags with "attribute": true).
struct AttributionSettings {
  uint32_t seeds = 2;              // renders per subset of oracles
  uint32_t oracle_seeds = 4;       // renders the seed-mean oracles average
  uint32_t oracle_frames = 16;     // ... each over its last this many frames (static scenes)
  uint32_t noise_spp = 16;         // samples per pixel of the two low-spp references the noise floor scales from
};

struct AttributeOptions {
  SuiteOptions suite;              // --case (one), --cases-dir, --goldens, --out, --device, --tier
  std::string technique;           // required
  std::string label;               // the case run's label ("" = the unlabelled run)
  std::string preset;              // "" = the run's first
  AttributionSettings settings;
};

int cmd_attribute(const AttributeOptions& o);

// The attribution of one row of `c` (at tier `tier`) on `gpu`: writes
// OUT/attribution/<case>.<row>.<preset>.json and .html (OUT = suite.out) and returns a summary
// for the suite's results: {"page", "json", "stages_in_game", "rois": [{"roi", "largest",
// "mse", "signed_energy", "oracle_floor"}]}. `verbose`: a line per render.
nlohmann::json attribute_row(Gpu& gpu, const Case& c, Tier tier, const TechniqueRun& run, const std::string& preset,
                             const AttributionSettings& s, const SuiteOptions& suite, bool verbose);

}  // namespace gib
