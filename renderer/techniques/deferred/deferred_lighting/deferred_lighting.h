// deferred_lighting: direct light (sun, sky and emissive surfaces by cosine rays, local lights;
// ray-traced shadows) on the G-buffer, dispatched per tile workload (DOOM: The Dark Ages,
// "Deferred Lighting", "Tile Classification"): one indirect dispatch per workload of
// tile_classify, each a permutation compiled without the features its tiles lack (the sky
// workload shades nothing; the opaque one has neither back-face transmission nor the cloth
// sheen lobe, the cloth one no transmission). With
// tile_classification 0 one uber kernel lights every pixel with every feature. Both run
// gib_direct_light() (renderer/passes/direct_lighting/direct_light.glsl), the code of the shared
// direct_lighting pass, so `deferred` and `direct` light a G-buffer the same way.
// Reads: G-buffer, vbuffer, tile_workloads (classified). Writes: direct_light.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_deferred_lighting_pass();
}
