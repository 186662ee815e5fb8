// Test shorthand for a technique's own settings (Settings::params<T>()) and its defaults.
#pragma once
#include <string>

#include "renderer/techniques/radiance_cache/radiance_cache.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"

namespace gib {

// Settings{} holding `technique`'s settings struct with its defaults (no preset applied).
inline Settings defaults_of(const std::string& technique) {
  return apply_options(find_technique(technique), Settings{}, {});
}
inline RadianceCacheSettings& rc(Settings& s) { return s.params<RadianceCacheSettings>(); }
inline const RadianceCacheSettings& rc(const Settings& s) { return s.params<RadianceCacheSettings>(); }
inline ReferenceSettings& ref(Settings& s) { return s.params<ReferenceSettings>(); }
inline const ReferenceSettings& ref(const Settings& s) { return s.params<ReferenceSettings>(); }
inline uint32_t& sky_rays(Settings& s) { return s.params<DirectLightingParams>().sky_rays; }
inline uint32_t sky_rays(const Settings& s) { return s.params<DirectLightingParams>().sky_rays; }

}  // namespace gib
