// What `gibench attribute` (attribute_command.h) reads for one row: the committed reference of
// each evaluation frame, the reference's noise floor, and the inputs of the technique's stage
// oracles (TechniqueStage::make): seed renders of the row, for a scene that changes with the
// scene frozen at an evaluation frame (the converged state there, the oracle of a stage with
// history), and the reference AOVs of that frame.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/attribution/attribute_command.h"
#include "harness/attribution/attribution.h"
#include "harness/goldens.h"
#include "renderer/techniques/technique.h"

namespace gib {

// The 1-based frame whose reference evaluates frame `f`: f when the case has per-frame
// references (case_render.h per_frame_references), else 0 (the case's one reference).
uint32_t reference_frame(const Case& c, uint32_t f);

// The committed reference of `aov` at reference frame `frame`; an error saying how to make it.
FloatImage read_reference(const GoldenStore& store, const Case& c, const std::string& aov, uint32_t frame);

// The reference's per-pixel variance (MSE units) per ROI at reference frame `frame`: two renders
// at `spp` with other seeds give 2 x the variance at that spp; the committed reference's is that
// x spp / its spp.
std::vector<double> reference_noise(Gpu& gpu, const Case& c, const std::string& aov, uint32_t spp,
                                    uint32_t committed_spp, const std::vector<attribution::NamedRoi>& rois,
                                    uint32_t frame);

// A row whose oracles are made: what oracle_inputs renders and reads.
struct OracleRow {
  Gpu& gpu;
  const Case& c;
  const TechniqueRun& run;
  const std::string& preset;
  const AttributionSettings& st;
  const GoldenStore& store;
  bool analytic;
  const std::string& aov;
  const Technique& t;
  bool verbose;
};

// What the oracles of the stages `game` (indices into t.stages) read: the reference AOVs, and
// the seed renders' resources after their last oracle_frames frames. `frozen` (1-based, 0 =
// off): the seed renders hold the scene as it is at that frame, and the references are that
// frame's. `elapsed`: seconds so far, for the progress lines.
OracleInputs oracle_inputs(const OracleRow& row, const std::vector<size_t>& game, uint32_t frozen,
                           const std::function<double()>& elapsed);

}  // namespace gib
