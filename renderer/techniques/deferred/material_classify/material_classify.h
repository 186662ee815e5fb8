// material_classify: builds, from the visibility buffer, one list of pixels per material
// shader, so deferred_texturing runs one pipeline per shader over exactly its pixels with one
// material per wave (DOOM: The Dark Ages, "Material Compute Dispatch", after [McLaren22]).
// Three kernels over 32x32 screen tiles:
//   material_classify_count  pixels per (tile, material), materials that are visible only
//   the prefix scan: segments ordered by shader, tile, material, each padded to kDeferredWave
//   entries; prefix sums give each segment's first slot, each shader's first wave and its
//   indirect dispatch args (one dispatch per shader pipeline covering all its waves: the seed's
//   grouped emulation of multi-indirect dispatch). Three kernels, so that no single workgroup
//   walks every entry:
//     material_classify_blocks   a workgroup per block of kMatScanSize entries: per shader, the
//                                block's padded slots, pixels and non-empty segments
//     material_classify_scan     one workgroup over the blocks' sums: each block's first slot,
//                                the args, the statistics
//     material_classify_offsets  a workgroup per block: each segment's first slot
//   Integer sums in a fixed order: the same words as one serial scan, on every run (tested
//   against material_scan_cpu).
//   material_classify_write  one workgroup per tile writes tile-local pixel coordinates
//                            (tile << 10 | y << 5 | x) in raster order within each segment: the
//                            lists are the same on every run (no atomics decide the order)
// Writes: material_segments (args, statistics, counts, offsets; deferred_shared.h),
// material_scan_blocks (the scan's per-block sums and first slots), pixel_commands (kDeferredPixelPad in padding). Statistics: classified pixels, waves, padding
// slots, non-empty segments. The shader of a material is its texture kind.
// Memory: pixel_commands holds pixels + segments * (kDeferredWave - 1) entries at most; it is
// sized for every (tile, material) segment being non-empty (bounded by one segment per pixel).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_material_classify_pass();
// Entries pixel_commands needs for a render size and material count (the bound above).
uint64_t material_command_capacity(uint32_t width, uint32_t height, uint32_t materials);
uint64_t material_segment_words(uint32_t width, uint32_t height, uint32_t materials);
// Blocks of kMatScanSize (tile, material) entries the scan splits the entries into (at least 1).
uint32_t material_scan_blocks(uint32_t width, uint32_t height, uint32_t materials);
// CPU mirror of the prefix scan: from the pixel counts of `seg` (material_segments' words, the
// counts at kSegHeader, `tiles` x the materials), the shader of each material (its texture kind,
// clamped as the kernels clamp it), writes the dispatch args, the scan's statistics and the
// offsets (0 for empty segments) the three scan kernels write.
void material_scan_cpu(std::vector<uint32_t>& seg, uint32_t tiles, const std::vector<uint32_t>& shader_of_material);
}  // namespace gib
