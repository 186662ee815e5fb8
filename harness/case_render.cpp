#include "harness/case_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "harness/goldens.h"
#include "renderer/techniques/technique.h"

namespace gib {

CaseRender render_case(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                       uint32_t seed_offset) {
  const Technique& t = find_technique(run.technique);
  Settings s;
  s.width = c.width;
  s.height = c.height;
  s.seed = c.reference_seed + seed_offset;
  s = apply_preset(t, preset, s);
  const bool reference = t.name == "reference";
  uint32_t frames = c.frames;
  if (reference) {
    s.spp_per_frame = std::min<uint32_t>(c.reference_spp, 16);
    while (c.reference_spp % s.spp_per_frame) --s.spp_per_frame;
  }
  s = apply_options(t, s, run.options);
  if (reference) frames = std::max(1u, c.reference_spp / s.spp_per_frame);

  std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  // A technique that produces the compared AOV itself (e.g. radiance-cache's indirect_diffuse)
  // is compared on that AOV; otherwise on its final output.
  bool own_aov = std::find(t.aovs.begin(), t.aovs.end(), aov) != t.aovs.end();
  std::string out_name = reference ? aov : (own_aov ? aov : t.output);
  std::vector<std::string> outputs{out_name};
  if (reference)
    for (auto& a : std::vector<std::string>{t.output, "direct", "indirect_diffuse"})
      if (std::find(outputs.begin(), outputs.end(), a) == outputs.end()) outputs.push_back(a);

  Executor ex(gpu, c.scene, s, make_passes(t), outputs);
  std::vector<FrameResult> results;
  for (uint32_t f = 0; f < frames; ++f) results.push_back(ex.run_frame());
  CaseRender r;
  r.technique = t.name;
  r.preset = preset;
  r.plan = ex.plan();
  r.passes = summarize(results);
  std::vector<double> totals;
  for (auto& fr : results) {
    totals.push_back(fr.total_ms);
    r.gpu_ms_total += fr.total_ms;
  }
  std::sort(totals.begin(), totals.end());
  r.frame_median_ms = totals.empty() ? 0 : totals[totals.size() / 2];
  r.frames = frames;
  r.spp = reference ? frames * s.spp_per_frame : 0;
  r.image = ex.read(out_name);
  if (reference)
    for (auto& a : outputs) r.aovs[a] = a == out_name ? r.image : ex.read(a);
  nlohmann::json key{{"case", c.name}, {"technique", t.name}, {"preset", preset}, {"options", run.options},
                     {"size", {c.width, c.height}}, {"frames", frames}, {"seed", s.seed},
                     {"spp", r.spp}, {"scene", c.scene_file.empty() ? std::string("inline") : c.scene_file}};
  r.settings_hash = fnv1a_hex(key.dump());
  return r;
}

}  // namespace gib
