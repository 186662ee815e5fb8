#include "renderer/scene/features.h"

namespace gib {

std::string_view feature_name(Feature f) {
  switch (f) {
    case Feature::sun: return "sun";
    case Feature::sky: return "sky";
    case Feature::local_lights: return "local_lights";
    case Feature::emissive: return "emissive";
    case Feature::alpha_tested: return "alpha_tested";
    case Feature::translucent: return "translucent";
    case Feature::textured: return "textured";
    case Feature::motion: return "motion";
    case Feature::decals: return "decals";
    case Feature::cloth: return "cloth";
    case Feature::indoor_volumes: return "indoor_volumes";
    case Feature::glossy: return "glossy";
  }
  return "unknown";  // a value cast from an integer that names no feature
}

std::string to_string(SceneFeatures f) {
  std::string out;
  for (uint32_t i = 0; i < 32; ++i) {
    uint32_t bit = 1u << i;
    if ((f.bits & bit) == 0) continue;
    if (!out.empty()) out += ',';
    // Bits beyond the known features are printed rather than hidden, so a stale mask shows up.
    if (i < kFeatureCount)
      out += feature_name(static_cast<Feature>(bit));
    else
      out += "bit" + std::to_string(i);
  }
  return out.empty() ? "none" : out;
}

}  // namespace gib
