// tile_classify: a 32-bit feature mask per 32x32 screen tile from the G-buffer, then one list
// of tiles and one indirect dispatch per lighting workload (DOOM: The Dark Ages, "Deferred
// Dispatches with Tile Classification").
//   tile_classify_mask  features of every pixel OR-ed into its tile's mask: with subgroup
//                       ballot, one atomicOr per distinct tile in the subgroup (the seed's
//                       scalarised loop); else one per pixel. Features (deferred_shared.h):
//                       sky, opaque, translucent, emissive.
//   tile_classify_args  one workgroup: each tile's workload from its mask (only sky: the sky
//                       workload; any translucent pixel: translucent; else opaque), the lists
//                       in tile order by prefix sums (the same on every run), the indirect
//                       arguments (kLightingGroupsPerTile workgroups per tile) and statistics.
// Writes: tile_workloads. Every tile has some pixel, so every tile runs one workload; the
// statistics say how many workgroups each workload took of the full-screen dispatch's.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_tile_classify_pass();
uint64_t tile_workload_words(uint32_t width, uint32_t height);
}  // namespace gib
