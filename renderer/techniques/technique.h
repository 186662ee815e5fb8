// Techniques: named compositions of passes with quality presets and options. Each technique
// is one folder, renderer/techniques/<name>/, whose <name>.cpp returns its Technique (pass
// list, output, AOVs, presets table, options bound to its own settings struct); the registry
// (technique_list.cpp) lists them, one line each. A technique lists every pass it may use;
// the graph culls what the scene or the requested outputs do not need.
#pragma once
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/image/float_image.h"

namespace gib {

// A named option of a technique: a settings field a case (or the CLI) may set directly,
// overriding the preset. Values are numbers in [min, max]; integer options reject fractions
// (switches are integers in [0, 1]).
struct TechniqueOption {
  std::string name;         // e.g. "sky_rays"
  std::string description;
  double min = 0;
  double max = 4294967295.0;
  bool integer = true;
  std::function<void(Settings&, double)> apply;
  std::function<double(const Settings&)> read;  // the value `s` holds (empty for options without a field)
  std::vector<double> allowed;  // when not empty, the only valid values (e.g. the NaN targets a technique has)
  // A pixel coordinate (column or row) of the render: a case rendered at another size (the GPU
  // tier, harness/tier.h) scales it so it names the same point of the image.
  enum class Pixel { no, column, row } pixel = Pixel::no;
};

// A pass the technique runs: its name (== folder == file stem == timer == bench key) and factory.
struct PassEntry {
  std::string name;
  std::unique_ptr<Pass> (*make)() = nullptr;
};

// Word i (uint32) of a buffer read back as bytes; 0 past its end.
inline uint32_t buffer_word(const std::vector<uint8_t>& bytes, uint64_t i) {
  uint32_t w = 0;
  if (i * 4 + 4 <= bytes.size()) std::memcpy(&w, bytes.data() + i * 4, 4);
  return w;
}

// A figure a technique counts on the GPU each frame (work skipped, pixels shaded at a coarse
// rate, ...): word `word` of buffer resource `resource`, divided by word `of_word` when that is
// set (a fraction). Reported per row as metric "stat_<name>" after the last frame; a case may
// bound it. Not reported when the resource is not in the run's plan (the step is switched off).
struct TechniqueStat {
  std::string name;
  std::string description;
  std::string resource;
  uint32_t word = 0;
  uint32_t of_word = UINT32_MAX;
};

// A debug view a technique draws on the CPU from one of its buffers after the last frame (the
// seed's debug visualisations: tile classes, shading rates). The runner saves it beside the
// row's output and the report shows it; no pass runs for it. Skipped when the resource is not in
// the run's plan.
struct TechniqueView {
  std::string name;
  std::string description;
  std::string resource;
  std::function<FloatImage(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height)> draw;
};

// A debug printout a technique writes on the CPU from one of its buffers after the last frame
// (the seed's shader-printf statistics, e.g. deferred's dispatched vs full-screen thread groups):
// plain text, saved in the row and shown in the report under its images.
struct TechniquePrintout {
  std::string name;
  std::string description;
  std::string resource;
  std::function<std::string(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height)> print;
};

// What a stage's oracle is made from (error attribution, harness/attribution/): renders of the
// technique as it is with other seeds (each listed resource's raw bytes after the last frame;
// images as tightly packed texels) and the case's path-traced reference AOVs.
struct OracleInputs {
  uint32_t width = 0, height = 0;                                  // render size
  std::vector<std::map<std::string, std::vector<uint8_t>>> seeds;  // per seed: resource -> bytes
  std::map<std::string, Format> formats;                           // resource -> its format
  std::map<std::string, std::pair<uint32_t, uint32_t>> extents;    // image resource -> its size
  std::map<std::string, FloatImage> reference;                     // contract AOV -> reference
};

// A stage for error attribution: consecutive passes grouped by what they compute, and its
// oracle, what the stage should output, written over its outputs after `after_pass` each frame
// (a graph override: no pass changes). A stage whose `make` is empty has no oracle yet and
// stays out of the game.
struct TechniqueStage {
  std::string name;
  std::vector<std::string> passes;
  std::string oracle;                        // what the oracle is, in words
  std::string after_pass;                    // writes every resource `make` returns, except:
  std::map<std::string, std::string> after_pass_of;  // resource -> the pass it is written after instead
  std::vector<std::string> seed_reads;       // resources the oracle reads from the seed renders
  std::vector<std::string> reference_aovs;   // reference AOVs it reads
  // Resource -> the bytes that replace it (its format; a buffer's one copy).
  std::function<std::map<std::string, std::vector<uint8_t>>(const OracleInputs&)> make;
};

struct Technique {
  std::string name;
  std::string description;
  std::vector<PassEntry> passes;     // in declaration order
  std::string output;                // the image the technique produces (its final radiance)
  std::vector<std::string> aovs;     // other outputs that may be requested (resources, e.g. for --dump)
  // The contract AOVs (aov.h) it produces exactly, each with the resource holding it; radiance
  // is always `output` and need not be listed. An AOV not listed is not comparable.
  std::map<std::string, std::string> contract_aovs;
  // Contract AOVs whose passes need scene features (e.g. gow-ragnarok's reflection: glossy): in a
  // scene without them the graph culls those passes and the AOV is not produced (by the contract
  // it would be 0 there). AOVs not listed are produced in every scene.
  std::map<std::string, SceneFeatures> contract_aov_needs;
  std::vector<std::string> presets;  // in order of quality: low, medium, high, ultra
  std::vector<TechniqueOption> options;  // in a stable order
  std::vector<TechniqueStat> stats;      // GPU counters reported per row
  std::vector<TechniqueView> views;      // debug views drawn from its buffers
  std::vector<TechniquePrintout> printouts;  // debug text printed from its buffers
  std::vector<TechniqueStage> stages;        // error attribution's stages, in pass order (3-6)
  // The technique's settings struct with its defaults, and the preset table applied to it
  // (row `level` of `presets`). Made by define_settings<T>().
  std::function<std::unique_ptr<TechniqueSettings>()> make_settings;
  std::function<void(Settings&, size_t level)> apply_preset_row;
};

// Binds a technique to its settings struct T and its presets table: `rows[i]` (a struct with a
// `name` and the values of preset i) applied by `apply(T&, const Row&)`.
template <class T, class Row, size_t N>
void define_settings(Technique& t, const Row (&rows)[N], void (*apply)(T&, const Row&)) {
  t.presets.clear();
  for (const Row& r : rows) t.presets.push_back(r.name);
  t.make_settings = [] { return std::make_unique<T>(); };
  t.apply_preset_row = [&rows, apply](Settings& s, size_t level) { apply(s.params<T>(), rows[level]); };
}

// An option bound to field `field` of P: the technique's settings struct or a shared pass's
// parameter struct it derives from. bool fields are switches in [0, 1].
template <class P, class V>
TechniqueOption option(std::string name, std::string description, double min, double max, V P::*field) {
  TechniqueOption o{std::move(name), std::move(description), min, max, !std::is_floating_point_v<V>};
  o.apply = [field](Settings& s, double v) {
    if constexpr (std::is_same_v<V, bool>)
      s.params<P>().*field = v != 0.0;
    else
      s.params<P>().*field = static_cast<V>(v);
  };
  o.read = [field](const Settings& s) { return static_cast<double>(s.params<P>().*field); };
  return o;
}

// Appends the options every technique shares: the NaN guards, the NaN-injection debug switches
// (the injection targets limited to `targets`, those the technique's passes write) and the
// world offset.
std::vector<TechniqueOption> with_common_options(std::vector<TechniqueOption> own, std::vector<double> targets);

// The resource holding contract AOV `aov` (aov.h) for `t`, or "" when `t` does not declare it
// (also "" for a name outside the contract).
std::string contract_resource(const Technique& t, const std::string& aov);
// The contract AOVs `t` declares, radiance first.
std::vector<std::string> contract_aov_names(const Technique& t);
// Those of them produced in a scene with these features (contract_aov_needs met).
std::vector<std::string> contract_aov_names(const Technique& t, SceneFeatures scene);

const std::vector<Technique>& techniques();
// Throws std::invalid_argument naming the known techniques when `name` is unknown.
const Technique& find_technique(const std::string& name);
// Settings for a preset: `base` with the technique's settings struct (kept when `base` already
// holds this technique's, else its defaults) and the preset's row applied. Throws
// std::invalid_argument on an unknown preset.
Settings apply_preset(const Technique& t, const std::string& preset, Settings base);
std::vector<std::unique_ptr<Pass>> make_passes(const Technique& t);
// Every pass of every technique, by name (shared passes once).
std::vector<std::string> pass_names();
// Throws GraphError naming the known passes when `name` is unknown.
std::unique_ptr<Pass> make_pass(const std::string& name);

// The options `t` accepts, in a stable order (empty for a technique with none).
const std::vector<TechniqueOption>& technique_options(const Technique& t);
// "" when `value` is valid for option `name` of `t`, else "expected <what>, got <what>"
// (for callers that prefix their own location, such as the case loader's JSON pointer).
std::string check_option(const Technique& t, const std::string& name, double value);
// Applies options on top of `base` (normally the preset's settings; given the technique's
// default settings struct when it holds another technique's). Throws std::invalid_argument
// naming the option: unknown names list the technique's known ones.
Settings apply_options(const Technique& t, Settings base, const std::map<std::string, double>& options);

}  // namespace gib
