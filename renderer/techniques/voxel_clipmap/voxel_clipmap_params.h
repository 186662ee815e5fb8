// Builds the push-constant block every voxel-clipmap pass shares from Settings, and the sizes of
// its buffers (C++ only).
#pragma once
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "renderer/graph/pass.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap.h"

namespace gib {

static_assert(sizeof(glsl::VcParams) == 64, "VcParams: 64 bytes in every voxel-clipmap push block");
static_assert(sizeof(glsl::VcState) == 4 * glsl::kVcMaxLevels * 16 + 32 && sizeof(glsl::VcQueue) == 32,
              "voxel-clipmap buffer structs: std430 sizes");

inline uint64_t vc_voxel_count(const VoxelClipmapSettings& p) { return uint64_t(p.levels) * p.grid * p.grid * p.grid; }
inline uint64_t vc_cell_count(const VoxelClipmapSettings& p) {
  const uint64_t m = p.grid / 2;
  return uint64_t(p.levels) * m * m * m;
}
// Voxels scene_voxel_light visits a frame (0 when geometry_light is off).
inline uint32_t vc_lit_visits(const VoxelClipmapSettings& p) {
  return p.geometry_light ? uint32_t(std::min<uint64_t>(p.lit_voxels, vc_voxel_count(p))) : 0u;
}
inline uint32_t vc_queue_capacity(const VoxelClipmapSettings& p) { return p.queue_a + p.queue_b; }

// Throws GraphError naming the setting when the clipmap cannot be built.
inline void check_vc_settings(const VoxelClipmapSettings& p) {
  if (p.levels == 0 || p.levels > glsl::kVcMaxLevels)
    throw GraphError(fmt::format("voxel-clipmap: levels must be 1..{}, got {}", glsl::kVcMaxLevels, p.levels));
  if (p.grid < 8 || p.grid > 128 || p.grid % 4 != 0)
    throw GraphError(fmt::format("voxel-clipmap: grid must be a multiple of 4 in 8..128, got {}", p.grid));
  if (p.rays_per_cell != 32 && p.rays_per_cell != 64 && p.rays_per_cell != 128 && p.rays_per_cell != 256)
    throw GraphError(fmt::format("voxel-clipmap: rays_per_cell must be 32, 64, 128 or 256, got {}", p.rays_per_cell));
  if (p.queue_a_new > p.queue_a)
    throw GraphError(fmt::format("voxel-clipmap: queue_a_new ({}) must not exceed queue_a ({})", p.queue_a_new, p.queue_a));
  if (p.queue_a + p.queue_b == 0) throw GraphError("voxel-clipmap: queue_a + queue_b must be at least 1");
}

// Whether direct_lighting's rays give every pixel its share of sky rays that met a surface
// (direct_light's alpha): sky rays traced through the BVH in a scene with a sky or emitters.
inline bool vc_pixel_sky_hits(const Scene& scene, const VoxelClipmapSettings& p) {
  const SceneFeatures f = scene.features();
  return p.sky_rays > 0 && !sky_unoccluded(p) && (f.has(Feature::sky) || f.has(Feature::emissive));
}

inline glsl::VcParams make_vc_params(const Scene& scene, const Settings& s, uint32_t frame) {
  const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
  check_vc_settings(p);
  using namespace glsl;
  const uint32_t flags = (s.nan_guards ? kVcFlagNanGuards : 0) | (p.convex_offset ? kVcFlagConvexOffset : 0) |
                         (p.geometry_fill ? kVcFlagGeometryFill : 0) | (p.semi_transparent ? kVcFlagSemiTransparent : 0) |
                         (p.sky_rays == 0 ? kVcFlagSkyFromCubes : 0) | (p.invalidate ? kVcFlagInvalidate : 0) |
                         (p.multi_bounce ? kVcFlagMultiBounce : 0) | (p.select_per_queue ? kVcFlagSelectPerQueue : 0) |
                         (p.geometry_light ? kVcFlagGeometryLight : 0) |
                         (p.wall_test == 1 ? kVcFlagWallWalk : 0) | (p.wall_test == 2 ? kVcFlagWallFlood : 0) |
                         (vc_pixel_sky_hits(scene, p) ? kVcFlagPixelSkyHits : 0);
  VcParams r{};
  r.grid = {p.grid, p.levels, frame, flags};
  r.sizes = {p.voxel_size, p.feed_weight, p.history_frames, 0};
  r.budget = {p.feed_pixels, p.queue_a, p.queue_a_new, p.queue_b};
  r.rays = {p.rays_per_cell, p.march_steps, s.seed, vc_lit_visits(p)};
  return r;
}

// A buffer resource of `bytes` (persistent: kept across frames).
inline ResourceDesc vc_buffer(uint64_t bytes, bool persistent) {
  ResourceDesc b{Format::buffer, SizeRule::buffer};
  b.bytes = bytes;
  b.persistent = persistent;
  return b;
}
// The persistent clipmap buffers, as every pass that touches them declares them.
inline ResourceDesc vc_state_desc() { return vc_buffer(sizeof(glsl::VcState), true); }
inline ResourceDesc vc_voxels_desc(const VoxelClipmapSettings& p) { return vc_buffer(vc_voxel_count(p) * 16, true); }
// Each voxel's third triangle + 1 (voxel_clipmap_shared.h), written by scene_voxel_fill.
inline ResourceDesc vc_third_desc(const VoxelClipmapSettings& p) { return vc_buffer(vc_voxel_count(p) * 4, true); }
inline ResourceDesc vc_cube_desc(const VoxelClipmapSettings& p) {
  ResourceDesc d = vc_buffer(vc_cell_count(p) * glsl::kVcCellFloats * 4, true);
  d.values = non_negative_values().layout(1, 0, 1);
  return d;
}
inline ResourceDesc vc_cell_state_desc(const VoxelClipmapSettings& p) { return vc_buffer(vc_cell_count(p) * 4, true); }
// Each cell's flood mask for the cube lookups' wall test (voxel_clipmap_shared.h), written by the
// relight. Only wall_test 2 writes or reads it; otherwise one word keeps the binding valid
// (the masks are 28 bytes a cell: 0.46 MB at 4 levels of 16^3 cells).
inline ResourceDesc vc_cell_vis_desc(const VoxelClipmapSettings& p) {
  return vc_buffer(p.wall_test == 2 ? vc_cell_count(p) * glsl::kVcCellVisWords * 4 : 4, true);
}

}  // namespace gib
