// The `reference` technique's settings (definition: reference.cpp).
#pragma once
#include <cstdint>

#include "renderer/graph/settings.h"

namespace gib {

struct ReferenceSettings : TechniqueSettingsOf<ReferenceSettings> {
  uint32_t spp_per_frame = 1;  // samples per pixel added each frame
  uint32_t max_bounces = 8;    // path length cap (Russian roulette after 3)
};

}  // namespace gib
