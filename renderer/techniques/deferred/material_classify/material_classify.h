// material_classify: builds, from the visibility buffer, one list of pixels per material
// shader, so deferred_texturing runs one pipeline per shader over exactly its pixels with one
// material per wave (DOOM: The Dark Ages, "Material Compute Dispatch", after [McLaren22]).
// Three kernels over 32x32 screen tiles:
//   material_classify_count  pixels per (tile, material), materials that are visible only
//   material_classify_scan   one workgroup: segments ordered by shader, tile, material, each
//                            padded to kDeferredWave entries; prefix sums give each segment's
//                            first slot, each shader's first wave and its indirect dispatch args
//                            (one dispatch per shader pipeline covering all its waves: the
//                            seed's grouped emulation of multi-indirect dispatch)
//   material_classify_write  one workgroup per tile writes tile-local pixel coordinates
//                            (tile << 10 | y << 5 | x) in raster order within each segment: the
//                            lists are the same on every run (no atomics decide the order)
// Writes: material_segments (args, statistics, counts, offsets; deferred_shared.h),
// pixel_commands (kDeferredPixelPad in padding). Statistics: classified pixels, waves, padding
// slots, non-empty segments. The shader of a material is its texture kind.
// Memory: pixel_commands holds pixels + segments * (kDeferredWave - 1) entries at most; it is
// sized for every (tile, material) segment being non-empty (bounded by one segment per pixel).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_material_classify_pass();
// Entries pixel_commands needs for a render size and material count (the bound above).
uint64_t material_command_capacity(uint32_t width, uint32_t height, uint32_t materials);
uint64_t material_segment_words(uint32_t width, uint32_t height, uint32_t materials);
}  // namespace gib
