// The `reference` technique's settings (definition: reference.cpp).
#pragma once
#include <cstdint>

#include "renderer/graph/settings.h"

namespace gib {

// Bump when the CPU side of what the path tracer renders changes (scene flattening, sampling
// setup, the spp split): with the SPIR-V of its passes and its ultra preset it keys the GPU
// tier's reference cache (harness/references.h path_tracer_revision), so cached references re-render.
inline constexpr uint32_t kPathTracerCpuRevision = 1;

struct ReferenceSettings : TechniqueSettingsOf<ReferenceSettings> {
  uint32_t spp_per_frame = 1;  // samples per pixel added each frame
  uint32_t max_bounces = 8;    // path length cap (Russian roulette after 3)
  uint32_t glossy_masking = 1;  // 0: the glossy lobe without Smith masking (a negative control)
};

}  // namespace gib
