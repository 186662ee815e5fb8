#include "renderer/techniques/technique.h"

#include <fmt/format.h>

#include <stdexcept>

#include "renderer/passes/pass_list.h"

namespace gib {

const std::vector<Technique>& techniques() {
  static const std::vector<Technique> t = {
      {"direct", "visibility buffer, G-buffer, direct light from sun, sky and local lights with ray-traced shadows",
       {"visibility", "gbuffer", "direct_lighting"}, "direct_light",
       {"vbuffer", "depth", "gbuffer_albedo", "gbuffer_normal", "gbuffer_position", "gbuffer_emissive"},
       {"low", "medium", "high", "ultra"}},
      {"reference", "progressive path tracer (ground truth)", {"path_trace", "path_trace_resolve"}, "radiance",
       {"direct", "indirect_diffuse"}, {"low", "medium", "high", "ultra"}},
  };
  return t;
}

const Technique& find_technique(const std::string& name) {
  std::vector<std::string> names;
  for (auto& t : techniques()) {
    if (t.name == name) return t;
    names.push_back(t.name);
  }
  throw std::invalid_argument(fmt::format("--technique: expected one of [{}], got '{}'", fmt::join(names, ", "), name));
}

Settings apply_preset(const Technique& t, const std::string& preset, Settings s) {
  static const char* kPresets[] = {"low", "medium", "high", "ultra"};
  int level = -1;
  for (int i = 0; i < 4; ++i)
    if (preset == kPresets[i]) level = i;
  if (level < 0) throw std::invalid_argument(fmt::format("preset: expected low|medium|high|ultra, got '{}'", preset));
  s.preset = preset;
  if (t.name == "direct") {
    static const uint32_t kSkyRays[] = {1, 4, 16, 64};
    s.sky_rays = kSkyRays[level];
  } else if (t.name == "reference") {
    static const uint32_t kBounces[] = {4, 8, 16, 64};
    s.max_bounces = kBounces[level];
  }
  return s;
}

std::vector<std::unique_ptr<Pass>> make_passes(const Technique& t) {
  std::vector<std::unique_ptr<Pass>> out;
  for (auto& p : t.passes) out.push_back(make_pass(p));
  return out;
}

}  // namespace gib
