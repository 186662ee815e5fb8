// composite: the radiance-cache technique's output. final_color = direct_light + albedo x
// gi_irradiance (gi_irradiance is irradiance / pi, so albedo x gi_irradiance is the Lambertian
// indirect radiance); indirect_diffuse = albedo x gi_irradiance (the AOV the reference's
// indirect_diffuse is compared with).
// Slots: reads direct_light, gbuffer_albedo, gi_irradiance; writes final_color (RGBA32F,
// persistent: final_gather reads last frame's copy as its screen cache, so the graph keeps two)
// and indirect_diffuse (RGBA32F).
// Seed: the idTech 8 "Global Illumination" talk, "Denoise and Upscale Passes" (step 4: adding direct
// lighting).
// Limits: diffuse only (no indirect specular / reflection probes); translucent surfaces get no
// back-side indirect light.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_composite_pass();
}
