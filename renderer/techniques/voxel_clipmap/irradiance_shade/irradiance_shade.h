// irradiance_shade: diffuse lighting from the irradiance clipmap per G-buffer pixel (Enlisted
// GDC 2019, 5.1 "Diffuse term" and "light leaking"): the finest level whose cell box holds the
// pixel's trilinear footprint, blended with the next coarser level over the two cells next to
// its border; trilinear over the eight cells around the point (by hand: the cubes are buffers),
// cells never relit left out; convex offset filtering (convex_offset) moves the lookup half a
// cell along the normal and drops corner cells behind the surface's plane, so a wall's far side
// does not leak into its near side. Writes gi_irradiance (bounce light, the AOV contract's
// indirect) and gi_direct_irradiance (the cubes' sky part, direct light, when direct_lighting
// traces no sky rays; else 0), both irradiance / pi, for composite. Where the pixel's sky rays
// counted the sky (direct_light's alpha: the share of them that met a surface), the bounce is
// gathered over that share only, so no direction is counted twice (vc_bounce_for_pixel).
// Slots: read voxel_clip_state, irradiance_x/_y/_z, irradiance_cell_state, gbuffer_normal,
// gbuffer_position, direct_light, scene_voxel_data (ordering only: the feed's voxels are this frame's);
// writes gi_irradiance, gi_direct_irradiance.
// Limits: no SSAO or specular term (5.2).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_irradiance_shade_pass();
}
