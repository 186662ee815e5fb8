// The `deferred` technique's settings (definition: deferred.cpp, design: deferred.md).
#pragma once
#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"

namespace gib {

struct DeferredSettings : TechniqueSettingsOf<DeferredSettings>, DirectLightingParams {
  bool classify_materials = true;    // texturing over per-shader pixel lists (false: one uber kernel)
  bool uniform_permutation = true;   // also dispatch the uniform-data permutation (where subgroups allow)
  bool tile_classification = true;   // lighting per tile workload (false: one uber kernel)
  bool gbuffer_update = true;        // blend decals into the G-buffer (false: a negative control, decals missing)
  bool sheen_lobe = true;            // light the cloth class's sheen lobe (false: a negative control, cloth as standard)
  // Variable-rate compute shading in the classified texturing and lighting dispatches.
  bool vrcs = false;
  float vrcs_threshold = 0.02f;  // largest tone-mapped luma step a coarse pair may hide
  bool vrcs_edges = true;        // instance changes and normal creases keep full rate
  uint32_t vrcs_force = 0;       // 0: chosen per tile; 1 2x1, 2 1x2, 3 2x2 everywhere (controls)
};

// 32x32 screen tiles of material and tile classification at a render size.
inline uint32_t deferred_tiles(uint32_t width, uint32_t height) {
  return div_up(width, glsl::kDeferredTile) * div_up(height, glsl::kDeferredTile);
}

}  // namespace gib
