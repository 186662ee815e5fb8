// composite: the output of a GI technique that writes gi_irradiance (probe-volume,
// voxel-clipmap), split by the AOV contract (renderer/techniques/aov.h). direct_radiance =
// direct_light (emission seen by the camera, sun, local lights) + albedo x gi_direct_irradiance
// (sky and emissive surfaces the gather reached with no further bounce); indirect_diffuse =
// albedo x gi_irradiance (bounce light; both are irradiance / pi, so albedo x E is the
// Lambertian radiance); final_color = direct_radiance + indirect_diffuse.
// Slots: reads direct_light, gbuffer_albedo, gi_irradiance, gi_direct_irradiance; writes
// final_color (RGBA32F, persistent: final_gather reads last frame's copy as its screen cache, so
// the graph keeps two), indirect_diffuse and direct_radiance (RGBA32F).
// Seed: the idTech 8 "Global Illumination" talk, "Denoise and Upscale Passes" (step 4: adding direct
// lighting).
// Limits: diffuse only (no indirect specular / reflection probes); translucent surfaces get no
// back-side indirect light.
#pragma once
#include <memory>
#include <vector>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_composite_pass();
// The slots every composite writes (this pass, and a technique's own composite that reads its
// indirect light from elsewhere): final_color, indirect_diffuse, direct_radiance, as above.
std::vector<Slot> composite_output_slots();
}
