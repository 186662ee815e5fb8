// Light grid lookups (owner: the light_grid pass; design: renderer/techniques/radiance_cache/radiance_cache.md).
//
// Layout of the `light_grid` buffer (uint words): cascades x 16^3 cells x kLightGridCellWords.
// Cell (x, y, z) of cascade c (x, y, z in 0..15, relative to the cascade's base cell) starts at
// word ((c * 16 + z) * 16 + y) * 16 + x) * 65; word 0 is the light count (<= 64), words
// 1..count the light ids (indices into gib_lights[]) in increasing order; words past the count
// are undefined. Cascade c spans LightGridParams.extent.x * 2^c metres; its cells are
// extent_c / 16 wide and its base cell is floor(camera / cell) - 8, so the grid follows the
// camera in whole cells (identical while the camera stays inside one cascade-0 cell).
//
// Use:
//   #include "frame.glsl"           // optional: enables the forms that read gib_frame.camera_pos
//   #define LG_PARAMS lg            // optional: any LightGridParams expression (e.g. push.lg);
//                                   // enables the one-argument lg_cell_base(p)
//   #include "renderer/techniques/radiance_cache/include/light_grid.glsl"
//   RC_LIGHT_GRID_BUFFER(binding)   // readonly buffer, set 0: uint light_grid[]
//   uint base = lg_cell_base(p);    // or lg_cell_base(p, params) / lg_cell_base(p, camera, params)
//   if (base != kLgInvalid)
//     for (uint i = 0u; i < LG_CELL_COUNT(base); ++i) { GpuLight l = gib_lights[LG_CELL_LIGHT(base, i)]; ... }
//
// LightGridParams (radiance_cache_shared.h): extent.x cascade-0 extent (m), extent.y cascades,
// extent.z scene light count. On the C++ side the light_grid pass fills it from
// Settings::rc.light_grid_extent / light_grid_cascades.
#ifndef GIB_LIGHT_GRID_GLSL
#define GIB_LIGHT_GRID_GLSL
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"

#define RC_LIGHT_GRID_BUFFER(B) \
  layout(std430, set = 0, binding = (B)) readonly buffer RcLightGridBuffer { uint light_grid[]; };
// Read a cell through the buffer declared by RC_LIGHT_GRID_BUFFER (macros: expanded where used).
#define LG_CELL_COUNT(base) light_grid[(base)]
#define LG_CELL_LIGHT(base, i) light_grid[(base) + 1u + (i)]

const uint kLgInvalid = 0xffffffffu;

uint lg_cascades(LightGridParams params) { return min(uint(params.extent.y), kMaxCascades); }

// Cell edge (m) of cascade c: extent * 2^c / 16 (exact for any extent: powers of two only).
float lg_cell_size(uint c, LightGridParams params) {
  return params.extent.x * float(1u << c) / float(kLightGridDim);
}

// Integer coordinates of a point in cells of edge `cell`, clamped so far points cannot overflow.
ivec3 lg_cell_coord(vec3 p, float cell) { return ivec3(clamp(floor(p / cell), vec3(-1e9), vec3(1e9))); }

// World cell coordinates of cell (0,0,0) of cascade c.
ivec3 lg_base_cell(uint c, vec3 camera, LightGridParams params) {
  return lg_cell_coord(camera, lg_cell_size(c, params)) - ivec3(int(kLightGridDim / 2u));
}

// Cell index (not word offset) of cell `local` (0..15 per axis) of cascade c.
uint lg_cell_index(uint c, uvec3 local) {
  return ((c * kLightGridDim + local.z) * kLightGridDim + local.y) * kLightGridDim + local.x;
}

// World-space bounds of cell `local` of cascade c.
void lg_cell_bounds(uint c, uvec3 local, vec3 camera, LightGridParams params, out vec3 bmin, out vec3 bmax) {
  float cell = lg_cell_size(c, params);
  ivec3 w = lg_base_cell(c, camera, params) + ivec3(local);
  bmin = vec3(w) * cell;
  bmax = vec3(w + ivec3(1)) * cell;
}

// Word offset of the cell holding p in the finest cascade containing it; kLgInvalid outside all.
uint lg_cell_base(vec3 p, vec3 camera, LightGridParams params) {
  uint n = lg_cascades(params);
  for (uint c = 0u; c < n; ++c) {
    ivec3 q = lg_cell_coord(p, lg_cell_size(c, params)) - lg_base_cell(c, camera, params);
    if (all(greaterThanEqual(q, ivec3(0))) && all(lessThan(q, ivec3(int(kLightGridDim)))))
      return lg_cell_index(c, uvec3(q)) * kLightGridCellWords;
  }
  return kLgInvalid;
}

#ifdef GIB_FRAME_GLSL
uint lg_cell_base(vec3 p, LightGridParams params) { return lg_cell_base(p, gib_frame.camera_pos.xyz, params); }
#ifdef LG_PARAMS
uint lg_cell_base(vec3 p) { return lg_cell_base(p, gib_frame.camera_pos.xyz, LG_PARAMS); }
#endif
#endif

#endif  // GIB_LIGHT_GRID_GLSL
