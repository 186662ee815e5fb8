// Constants and buffer layouts shared by the deferred technique's passes (C++ and GLSL).
#ifndef GIB_DEFERRED_SHARED_H
#define GIB_DEFERRED_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
// Screen tiles of material classification and of tile classification: 32x32 pixels, so a
// tile-local coordinate is 5 + 5 bits (the seed's tile size for lights, decals and features).
GIB_CONST(uint, kDeferredTile, 32)
GIB_CONST(uint, kDeferredTileShift, 5)
// Pixel lists are padded per (shader, tile, material) segment to this many entries, so one
// workgroup of this size shades one material (the seed pads to the hardware wave size; ours is
// fixed so the lists are the same on every device).
GIB_CONST(uint, kDeferredWave, 64)
// Material shaders: one texturing pipeline per texture kind (TextureKind: none, checker,
// value_noise, image).
GIB_CONST(uint, kDeferredShaderCount, 4)
GIB_CONST(uint, kDeferredPixelPad, 0xffffffffu)  // an empty entry of a padded list
// Pixel command: tile index << 10 | local y << 5 | local x.

// Buffer `material_segments` (uint words):
//   [4 s .. 4 s + 3]          shader s: indirect dispatch args (waves, 1, 1) and its first wave
//   [kSegStats + i]           statistics (kStat*)
//   [kSegHeader + e]          per (tile, material) e = tile * materials + material: pixel count
//   [kSegHeader + E + e]      its first slot in pixel_commands (E = tiles * materials)
GIB_CONST(uint, kSegStats, 16)
GIB_CONST(uint, kStatPixels, 0)             // classified pixels (not sky)
GIB_CONST(uint, kStatWaves, 1)              // padded waves over all shaders
GIB_CONST(uint, kStatPaddingSlots, 2)       // empty entries in the padded lists
GIB_CONST(uint, kStatSubgroupsUniform, 3)   // texturing subgroups that took the uniform-data path
GIB_CONST(uint, kStatSubgroupsDivergent, 4) // ... the divergent path
GIB_CONST(uint, kStatSegments, 5)           // non-empty (tile, material) segments
GIB_CONST(uint, kSegHeader, 32)

// Buffer `tile_workloads` (uint words):
//   [4 w .. 4 w + 3]          list w: indirect args (groups, 1, 1) and its tile count
//   [kTileStats + i]          statistics
//   [kTileHeader + w * T + i] tile indices of list w (T = tiles)
//   [kTileHeader + L * T + t] tile t's feature mask (L = kTileListCount)
// Lists 0 .. kWorkloadCount - 1 are the lighting workloads (each tile in exactly one: the
// cheapest permutation that has every feature the tile has); list kTileListDecals holds the
// tiles some decal touches, over which gbuffer_update runs (a tile may be in both).
GIB_CONST(uint, kWorkloadSky, 0)          // sky only: the sky's radiance, no shading
GIB_CONST(uint, kWorkloadOpaque, 1)       // opaque surfaces of the standard BRDF (and sky)
GIB_CONST(uint, kWorkloadCloth, 2)        // ... and the cloth BRDF's sheen lobe
GIB_CONST(uint, kWorkloadTranslucent, 3)  // some pixel transmits light through its back face (every feature)
GIB_CONST(uint, kWorkloadCount, 4)
GIB_CONST(uint, kTileListDecals, 4)
GIB_CONST(uint, kTileListCount, 5)
GIB_CONST(uint, kTileStats, 24)
GIB_CONST(uint, kTileStatTiles, 0)  // tiles on screen (the full-screen dispatch's share is 1)
GIB_CONST(uint, kTileHeader, 32)
// Feature bits of a tile's mask (32 available; the seed's TC_FEATURE_* bits).
GIB_CONST(uint, kTileFeatureSky, 1)
GIB_CONST(uint, kTileFeatureOpaque, 2)
GIB_CONST(uint, kTileFeatureTranslucent, 4)
GIB_CONST(uint, kTileFeatureEmissive, 8)
GIB_CONST(uint, kTileFeatureCloth, 16)   // the seed's TC_FEATURE_BRDF_CLOTH
GIB_CONST(uint, kTileFeatureDecals, 32)  // the seed's TC_FEATURE_DECALS: some decal covers a pixel
// Lighting runs 8x8 workgroups: 16 per 32x32 tile.
GIB_CONST(uint, kLightingGroup, 8)
GIB_CONST(uint, kLightingGroupsPerTile, 16)

// Variable-rate compute shading (VRCS): one rate per 8x8 pixel tile in buffer `vrcs_rates`
//   [kVrcsStats + i]   statistics; [kVrcsHeader + t] rate of tile t: bit 0 coarse in x, bit 1 in y
// A coarse cell is 2x1, 1x2 or 2x2 pixels aligned in its tile; its anchor (top-left pixel) shades
// and writes its result to the cell's pixels of the same instance, whose invocations retire.
GIB_CONST(uint, kVrcsTile, 8)
GIB_CONST(uint, kVrcsCoarseX, 1)
GIB_CONST(uint, kVrcsCoarseY, 2)
GIB_CONST(uint, kVrcsStats, 0)
GIB_CONST(uint, kVrcsStatTiles, 0)     // tiles per rate: words 0..3 (1x1, 2x1, 1x2, 2x2)
// (each count is followed by its total: gib_vrcs_count writes word and word + 1)
GIB_CONST(uint, kVrcsStatTextured, 4)  // texturing: pixels whose material was evaluated
GIB_CONST(uint, kVrcsStatTexturedOf, 5)  // ... of this many geometry pixels
GIB_CONST(uint, kVrcsStatLit, 6)       // lighting: geometry pixels lit by their own invocation
GIB_CONST(uint, kVrcsStatLitOf, 7)     // ... of this many geometry pixels
GIB_CONST(uint, kVrcsStatDecaled, 8)   // gbuffer_update: geometry pixels of decal tiles that evaluated the decals
GIB_CONST(uint, kVrcsStatDecaledOf, 9) // ... of this many geometry pixels of decal tiles
GIB_CONST(uint, kVrcsHeader, 16)
GIB_SHARED_END
#endif
