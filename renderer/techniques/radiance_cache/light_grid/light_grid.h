// light_grid: cascaded world-space light grid (idTech 8 "Lighting the RT World", seed
// the idTech 8 "Global Illumination" talk, "Cascaded Light Grid" and its hierarchical
// gather). Cascade c of light_grid_cascades spans light_grid_extent * 2^c metres in 16^3 cells,
// centred on the camera snapped to that cascade's cell size (base cell floor(camera / cell) - 8),
// so the grid does not change while the camera moves inside one cascade-0 cell. One dispatch of
// 4 x 4 x (4 * cascades) groups of 4x4x4 threads; a group covers a 4x4x4 block of cells.
// Coarse culling: the group's threads test every light against the block's union box and set
// bits in a group-shared flat bit array (4096 bits, ordered by light index). Detailed culling:
// each thread tests its cell box against the set bits and writes up to 64 ids, in order.
// Test: sphere of radius `range` vs cell box; spot lights additionally by a conservative
// bounding-sphere-vs-outer-cone rejection (LightGridOptions::cone_cull, on by default).
// Slots: needs local_lights (culled otherwise); reads the scene lights; writes `light_grid`
// (buffer, cascades x 16^3 x 65 uint; layout in renderer/techniques/radiance_cache/include/light_grid.glsl) and
// `light_grid_stats` (buffer, LightGridStats: overflowed_cells, max_lights_in_a_cell).
// Limits: only the first 4096 scene lights (kLightGridSceneLights, the seed's retail limit) are
// binned; a cell overlapped by more than 64 lights keeps the 64 lowest ids (counted in
// light_grid_stats.overflowed_cells); at most kMaxCascades (8) cascades. Only lights are binned
// (the seed also bins reflection probes and decals); the seed's CPU per-cascade containment
// bitmask is not needed at these light counts (coarse culling skips absent lights cheaply).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/techniques/radiance_cache/light_grid/light_grid_shared.h"

namespace gib {

struct LightGridOptions {
  bool cone_cull = true;  // spot lights: also reject cells outside the outer cone
};
std::unique_ptr<Pass> make_light_grid_pass(LightGridOptions options = {});

// ---- CPU mirror of the grid geometry and culling (same float operations as the shaders).
inline constexpr uint32_t kLightGridInvalid = 0xffffffffu;
glsl::LightGridParams make_light_grid_params(const Settings& settings, uint32_t light_count);
uint32_t light_grid_cascades(const glsl::LightGridParams& params);
uint32_t light_grid_words(const glsl::LightGridParams& params);  // buffer size in uints
float light_grid_cell_size(const glsl::LightGridParams& params, uint32_t cascade);
// World cell coordinates of cell (0,0,0) of a cascade.
void light_grid_base_cell(const glsl::LightGridParams& params, uint32_t cascade, Vec3 camera, int32_t out[3]);
void light_grid_cell_bounds(const glsl::LightGridParams& params, uint32_t cascade, const uint32_t local[3],
                            Vec3 camera, Vec3& bmin, Vec3& bmax);
// Word offset of cell `local` of `cascade` (its count word).
uint32_t light_grid_cell_word(uint32_t cascade, const uint32_t local[3]);
// lg_cell_base: word offset of the cell holding p in the finest cascade containing it, or
// kLightGridInvalid outside every cascade.
uint32_t light_grid_cell_of(const glsl::LightGridParams& params, Vec3 camera, Vec3 p);
// Every light (index order, not capped at 64, first kLightGridSceneLights only) whose sphere
// overlaps the cell box and, with cone_cull, whose outer cone may touch it.
std::vector<uint32_t> lights_for_cell(const std::vector<GpuLight>& lights, const glsl::LightGridParams& params,
                                      uint32_t cascade, const uint32_t local[3], Vec3 camera, bool cone_cull);

}  // namespace gib
