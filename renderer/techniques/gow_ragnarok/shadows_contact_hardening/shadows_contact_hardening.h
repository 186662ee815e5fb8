// shadows_contact_hardening: the sun's visibility per G-buffer pixel by marching rays through
// the shadow map towards an area light (filter radius in size, march_distance from the pixel):
// all rays stepped together, a ray stops where its sample and the disk sample below it
// disagree (the depth map taken as contiguous, so the worst case is PCF, never a leak);
// filtered taps, pattern turned per pixel; the dilated min/max skips fully lit or shadowed
// pixels and ends the march where nothing can occlude any more.
// Slots: reads gbuffer_position, gbuffer_normal, shadow_map, shadow_minmax; writes
// shadow_contact_hardening (r32_float, render size).
// Seed: God of War Ragnarök, "Contact Hardening Shadows" (3.22 / 3.15 ms at 4K).
// Limits: not physical, as the seed's: the area light sits march_distance away, so penumbrae
// stop widening beyond it; physical where filter_radius = 0 (the sun's size) and occluders are
// within march_distance.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_shadows_contact_hardening_pass();
}
