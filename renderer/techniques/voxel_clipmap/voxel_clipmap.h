// The `voxel-clipmap` technique's settings (definition: voxel_clipmap.cpp; design notes:
// voxel_clipmap.md). Presets and case options set them; its passes read them with
// Settings::params<VoxelClipmapSettings>().
#pragma once
#include <cstdint>

#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"

namespace gib {

struct VoxelClipmapSettings : TechniqueSettingsOf<VoxelClipmapSettings>, DirectLightingParams {
  // Sky and emissive surfaces reach the first visible surface through direct_lighting's sky
  // rays (the AOV contract's `direct`, exactly); the irradiance clipmap's bounce part carries
  // the rest. sky_rays 0 takes sky and emitters from the clipmap's direct part instead (the
  // seed's "indirect lighting + sky light" map): cheaper, but `direct` then carries the voxel
  // approximation (voxelised occlusion, trilinear cells), not the contract's exact light.
  VoxelClipmapSettings() { sky_rays = 4; }
  // ---- scene voxels (Enlisted GDC 2019, 4.1-4.3)
  uint32_t levels = 4;            // nested levels, voxel size doubling per level
  uint32_t grid = 32;             // voxels per axis per level (cells: grid / 2)
  float voxel_size = 0.25f;       // level-0 voxel edge (m); irradiance cells are twice that
  uint32_t feed_pixels = 32768;   // K: G-buffer pixels fed into the voxels per frame
  float feed_weight = 0.2f;       // exponential-average weight of a new sample (never-fed voxels: 1)
  bool geometry_fill = true;      // new voxels take opacity from the scene's triangles (the talk's collision model)
  bool invalidate = true;         // voxels in the box of moved geometry are cleared and refilled
  bool semi_transparent = true;   // alpha-tested surfaces give voxels their mean opacity (< 1)
  bool multi_bounce = true;       // fed pixels add albedo x the irradiance clipmap's bounce (0: one bounce)
  bool geometry_light = true;     // voxels no pixel fed are lit from their triangle (4.2's "actual rendering models")
  uint32_t lit_voxels = 32768;    // voxels scene_voxel_light visits per frame (a window moving over the atlas)
  // ---- irradiance clipmap (3.1)
  uint32_t queue_a = 1024;        // capacity of queue A (cells with geometry), A' included
  uint32_t queue_a_new = 128;     // capacity of queue A' (cells with geometry never relit)
  uint32_t queue_b = 128;         // capacity of queue B (empty cells)
  uint32_t rays_per_cell = 64;    // one thread per ray: 32, 64, 128 or 256
  uint32_t march_steps = 256;     // voxels a ray visits at most
  float history_frames = 8.0f;    // age-weighted temporal weight: min(1, age / history_frames)
  bool select_per_queue = false;  // one P for cells with geometry (queue A), one for empty cells (queue B)
  // ---- shading (5.1)
  bool convex_offset = true;      // lookup moved along the normal, corners behind the surface dropped
  // With geometry_light, cube lookups skip cells behind another wall: 0 no test, 1 a voxel walk per
  // pixel and cell through the kept triangles' planes, 2 one bit of the cell's flood mask
  // (irradiance_cell_vis, written by the relight; the walk where it has no answer). 1 stays the
  // default: 2 over-lights gltf-atrium's colonnade (voxel_clipmap.md, "Convex offset filtering").
  uint32_t wall_test = 1;
};

}  // namespace gib
