// `gibench attribute --case C --technique T [--preset P] [--seeds K]`: error attribution of one
// case row (attribution.h) with the technique's stages and oracles (Technique::stages): renders
// every subset of oracles x seeds, prints a table per ROI and writes
// OUT/attribution/<case>.<row>.<preset>.json and a waterfall page (.html) beside it.
#pragma once
#include <cstdint>
#include <string>

#include "harness/suite.h"

namespace gib {

struct AttributeOptions {
  SuiteOptions suite;              // --case (one), --cases-dir, --goldens, --out, --device, --tier
  std::string technique;           // required
  std::string label;               // the case run's label ("" = the unlabelled run)
  std::string preset;              // "" = the run's first
  uint32_t seeds = 2;              // renders per subset of oracles
  uint32_t oracle_seeds = 4;       // renders the seed-mean oracles average
  uint32_t noise_spp = 16;         // samples per pixel of the two low-spp references the noise floor scales from
};

int cmd_attribute(const AttributeOptions& o);

}  // namespace gib
