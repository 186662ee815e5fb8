// reflections_rt_cubemap: "Raytraced Cubemaps" (god-of-war-ragnarok-rendering.txt): at half
// resolution, one GGX reflection ray per glossy pixel (visible-normal sampling of the pixel's
// lobe, brdf.glsl), then 1. a screen-space trace against the G-buffer (hit: the lit screen's
// colour there, cyan); 2. where it finds nothing, a BVH trace (the seed traces proxy geometry;
// here the scene's own BVH); a hit that shows on screen takes the screen's colour (purple), one
// that does not samples the cube map in the direction from the capture point to the hit (the
// "raytraced cubemap", yellow); a miss reads the sky. Mode 0 (option reflection_mode, the
// baseline): the parallax-corrected cube map alone, box-projected from the pixel (Lagarde 2012).
// The sample is weighted by the lobe (F G2 / G1: f cos / pdf of the VNDF sample), so the output
// estimates the `reflection` AOV (aov.h). This pass is the seed's trace and combine in one
// (the combine's screen-or-cube-map choice is made per ray here).
// Slots: read vbuffer, gbuffer_position, gbuffer_normal, gbuffer_albedo, direct_light,
// reflection_cubemap; write reflection_trace (rgba32f, half: weighted colour, a = 1 on glossy
// pixels), reflection_stats (buffer: kReflStat* counters).
// Needs: glossy.
// Limits: the screen holds direct light only (gow-ragnarok has no GI yet), so reflections of
// on-screen surfaces miss their bounce light, which the cube map (baked with it) has; one
// reflection ray per half-resolution pixel per frame, the resolve averages over frames.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_reflections_rt_cubemap_pass();
}
