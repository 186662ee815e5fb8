// Techniques: named compositions of passes with quality presets. A technique lists every pass
// it may use; the graph culls what the scene or the requested outputs do not need.
#pragma once
#include <string>
#include <vector>

#include "renderer/graph/pass.h"

namespace gib {

struct Technique {
  std::string name;
  std::string description;
  std::vector<std::string> passes;   // in declaration order
  std::string output;                // the image the technique produces (its final radiance)
  std::vector<std::string> aovs;     // other outputs that may be requested
  std::vector<std::string> presets;  // low, medium, high, ultra
};

const std::vector<Technique>& techniques();
// Throws std::invalid_argument naming the known techniques when `name` is unknown.
const Technique& find_technique(const std::string& name);
// Settings for a preset: throws std::invalid_argument on an unknown preset.
Settings apply_preset(const Technique& t, const std::string& preset, Settings base);
std::vector<std::unique_ptr<Pass>> make_passes(const Technique& t);

}  // namespace gib
