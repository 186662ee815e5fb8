#include "renderer/techniques/technique.h"

#include <fmt/format.h>

#include <cmath>
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

namespace {

uint32_t* option_field(const std::string& technique, const std::string& name, Settings& s) {
  if (technique == "direct" && name == "sky_rays") return &s.sky_rays;
  if (technique == "reference" && name == "max_bounces") return &s.max_bounces;
  if (technique == "reference" && name == "spp_per_frame") return &s.spp_per_frame;
  return nullptr;
}

std::string option_value_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}

}  // namespace

const std::vector<TechniqueOption>& technique_options(const Technique& t) {
  static const std::vector<TechniqueOption> kDirect = {
      {"sky_rays", "sky visibility rays per pixel (0: no sky light)", 0},
  };
  static const std::vector<TechniqueOption> kReference = {
      {"max_bounces", "path length cap (1: direct light only, no interreflection)", 1},
      {"spp_per_frame", "samples per pixel added each frame", 1},
  };
  static const std::vector<TechniqueOption> kNone;
  if (t.name == "direct") return kDirect;
  if (t.name == "reference") return kReference;
  return kNone;
}

std::string check_option(const Technique& t, const std::string& name, double value) {
  const auto& opts = technique_options(t);
  for (const auto& o : opts) {
    if (o.name != name) continue;
    if (!std::isfinite(value) || value != std::floor(value) || value < o.min || value > o.max)
      return fmt::format("expected an integer in [{}, {}], got {}", o.min, o.max, option_value_text(value));
    return "";
  }
  std::vector<std::string> names;
  for (const auto& o : opts) names.push_back(o.name);
  return fmt::format("expected one of the options of {} ({}), got unknown option \"{}\"", t.name,
                     names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", ")), name);
}

Settings apply_options(const Technique& t, Settings s, const std::map<std::string, double>& options) {
  for (const auto& [name, value] : options) {
    std::string err = check_option(t, name, value);
    if (!err.empty()) throw std::invalid_argument(fmt::format("option \"{}\": {}", name, err));
    if (uint32_t* field = option_field(t.name, name, s)) *field = static_cast<uint32_t>(value);
  }
  return s;
}

}  // namespace gib
