// The direct-light modes every technique running direct_lighting (or deferred's
// deferred_lighting) offers: option `direct_light`, 0 traced (the default: the reference's light
// paths, for the accuracy checks) or 1 shadow_mapped (the sun through the cascaded shadow map and
// PCF, the sky unoccluded: what a shipped game's frame pays; DirectLightingParams,
// docs/architecture.md "Direct light modes"). A technique appends these passes and options to its
// own; the graph culls the shadow passes in the traced mode (nothing reads their outputs).
#pragma once
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib {

// shadow_maps, shadow_minmax, shadows_pcf (renderer/passes/).
std::vector<PassEntry> sun_shadow_passes();
// The `direct_light` option (DirectLightingParams::direct_light).
TechniqueOption direct_light_option();
// `direct_light` and the shadow map's main settings under their field names (shadow_resolution,
// shadow_cascades, shadow_distance, shadow_bias, shadow_normal_offset, shadow_taps), for
// techniques whose own options do not already bind them (gow-ragnarok's do).
std::vector<TechniqueOption> direct_light_options();
// Appends sun_shadow_passes() and direct_light_options() to `t` (after its own passes and
// options): one line in a technique's definition.
void add_direct_light_modes(Technique& t);

}  // namespace gib
