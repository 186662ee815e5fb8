// cubemap_capture: the parallax-corrected cube map of "Raytraced Cubemaps" (god-of-war-ragnarok-
// rendering.txt: "God of War: Ragnarok uses parallax-corrected cubemaps (Lagarde2012)"), baked
// here by path tracing the BVH from the capture point: one path per texel per frame, accumulated
// across frames into a persistent sum (the game bakes offline; this converges while a case warms
// up). Proxy box: the scene's bounds (the BVH root's box); capture point: its centre.
// Paths: Lambertian at every hit (glossy materials read as their albedo), NEE towards the sun and
// local lights, sky on a miss, emission; `cubemap_bounces` vertices.
// Slots: read_write reflection_cubemap (rgba32f, 6N x N, persistent: sum rgb, count a).
// Needs: glossy (nothing reflects without a glossy material).
// Limits: one box and one capture point per scene (the game places many, authored in Maya);
// nearest-texel look-ups, no prefiltered mips (the readers sample the lobe instead); alpha-tested
// surfaces are opaque to the capture's rays.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_cubemap_capture_pass();
}
