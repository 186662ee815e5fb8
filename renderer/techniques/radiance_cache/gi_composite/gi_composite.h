// gi_composite: radiance-cache's output, split by the AOV contract (renderer/techniques/aov.h),
// straight from the temporal filter's history. direct_radiance = direct_light (emission seen by
// the camera, sun, local lights) + albedo x gi_direct_irradiance (sky and emissive surfaces the
// gather reached with no further bounce); indirect_diffuse = albedo x gi_irradiance (bounce
// light); final_color = direct_radiance + indirect_diffuse. gi_irradiance and
// gi_direct_irradiance are this frame's gi_history and gi_history_direct / P_now (word 0 of
// `exposure`), computed here as gi_resolve computes them, so the result is bit for bit what the
// shared `composite` pass makes of gi_resolve's images, without writing and reading back two
// RGBA32F images (32 bytes a pixel each way): 4 + 4 bytes of RGB9E5 history a pixel instead.
// Slots: reads direct_light, gbuffer_albedo, gi_history, gi_history_direct, exposure; writes
// final_color (RGBA32F, persistent: final_gather reads last frame's copy as its screen cache, so
// the graph keeps two), indirect_diffuse and direct_radiance (RGBA32F).
// One kernel per history format (gi_composite_<format>.comp, include/gi_history.glsl).
// Seed: the idTech 8 "Global Illumination" talk, "Denoise and Upscale Passes" (adding direct
// lighting).
// Limits: diffuse only (no indirect specular / reflection probes); translucent surfaces get no
// back-side indirect light.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gi_composite_pass();
}
