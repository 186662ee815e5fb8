// Techniques: named compositions of passes with quality presets. A technique lists every pass
// it may use; the graph culls what the scene or the requested outputs do not need.
#pragma once
#include <map>
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

// A named option of a technique: a Settings field a case (or the CLI) may set directly,
// overriding the preset. Values are numbers in [min, max]; integer options reject fractions
// (switches are integers in [0, 1]).
struct TechniqueOption {
  std::string name;         // e.g. "sky_rays"
  std::string description;
  double min = 0;
  double max = 4294967295.0;
  bool integer = true;
  void (*apply)(Settings&, double) = nullptr;
  std::vector<double> allowed;  // when not empty, the only valid values (e.g. the NaN targets a technique has)
};

// The options `t` accepts, in a stable order (empty for a technique with none).
const std::vector<TechniqueOption>& technique_options(const Technique& t);
// "" when `value` is valid for option `name` of `t`, else "expected <what>, got <what>"
// (for callers that prefix their own location, such as the case loader's JSON pointer).
std::string check_option(const Technique& t, const std::string& name, double value);
// Applies options on top of `base` (normally the preset's settings). Throws
// std::invalid_argument naming the option: unknown names list the technique's known ones.
Settings apply_options(const Technique& t, Settings base, const std::map<std::string, double>& options);

}  // namespace gib
