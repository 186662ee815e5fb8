// gbuffer_update: blends the scene's projected decals into the G-buffer albedo after deferred
// texturing (DOOM: The Dark Ages, "Deferred G-Buffer Update & Lighting": "blend G-buffer
// modifications ... only write touched G-buffer channels"; its tile-classification statistics
// for the G-buffer update). Dispatched indirectly over the 32x32 tiles tile_classify found some
// decal in (kTileListDecals; the seed's Siege scene dispatched 68 % of its tiles), or over every
// pixel with tile_classification 0. With VRCS the anchor of a coarse cell evaluates the decals
// once and applies them to each covered pixel's own albedo. The decal code is decals.glsl, which
// the gbuffer pass and the path tracer run too.
// Reads: vbuffer, gbuffer_position, gbuffer_normal, tile_workloads (classified), vrcs_rates
// (VRCS). Modifies: gbuffer_albedo (rgb, only where a decal covers). Needs: decals (culled
// without them).
// Limits: projected decals only (the seed also has geometry decals, wetness and blood layers);
// decals change albedo only (no normal or roughness channels in our G-buffer).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gbuffer_update_pass();
}
