// shadow_maps: cascaded shadow maps for the sun. Rasterises every triangle once per cascade
// (one draw each, into its square of an atlas: cascades side by side) with an orthographic
// projection along the sun; the cascades bound view-frustum slices (splits: the practical
// scheme between the camera's near plane and shadow_distance), snapped to whole texels.
// Depth 0 is nearest the sun; it is written to a colour target (r32f) that compute passes read.
// Slots: writes shadow_map (r32_float, fixed: resolution x cascades by resolution),
//        shadow_depth (d32_float, the raster's depth test).
// Seed: God of War Ragnarök, "Contact Hardening Shadows" (the shadow map its PCF and ray march
// read; the talk does not detail its cascades: the split scheme is ours).
// Limits: orthographic cascades fitted to bounding spheres (no tight fit to the receivers);
// casters more than caster_range metres beyond a cascade's sphere towards the sun are clipped.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_shadow_maps_pass();
}
