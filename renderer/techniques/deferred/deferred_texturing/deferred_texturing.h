// deferred_texturing: the G-buffer from the visibility buffer and the interpolated attributes,
// one compute pipeline per material shader (procedural texture kind) dispatched indirectly over
// that shader's pixel lists (DOOM: The Dark Ages, "Deferred Texturing"). Each list is dispatched
// twice where the device has subgroup vote, ballot and arithmetic: a uniform-data permutation that takes
// subgroups whose pixels share one instance (broadcasting it) and a divergent one for the rest
// (the seed's subgroupAllEqual / subgroupBroadcastFirst trick); without them, or with
// uniform_permutation 0, once. Counts of subgroups on each path go to material_segments.
// With classify_materials 0 one uber kernel textures every pixel, switching on the material's
// shader per pixel; both call the same function, so they agree bit for bit.
// Reads: vbuffer, vis_bary, vis_bary_deriv, vis_tangent_frame, material_segments,
// pixel_commands. Writes: gbuffer_albedo, gbuffer_normal, gbuffer_position, gbuffer_emissive
// (the shared G-buffer layout, so the shared lighting code reads it unchanged).
// NaN injection target 1 (a NaN normal at a geometry pixel) as the gbuffer pass.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_deferred_texturing_pass();
}
