// light_grid pass: bindings, group size, push constants and stats layout (C++ and GLSL).
// The grid layout itself (kLightGridDim, kLightGridCellWords, LightGridParams) is the
// technique's contract in radiance_cache_shared.h.
#ifndef GIB_LIGHT_GRID_SHARED_H
#define GIB_LIGHT_GRID_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kLightGridGroup, 4)            // 4x4x4 threads = one coarse cell of 4x4x4 grid cells
GIB_CONST(uint, kLightGridSceneLights, 4096)   // lights considered (the seed's retail limit); more are ignored
GIB_CONST(uint, kLightGridBitWords, 128)       // kLightGridSceneLights / 32: group-shared flat bit array
GIB_CONST(uint, kLightGridBindGrid, 8)         // writeonly uint light_grid[]
GIB_CONST(uint, kLightGridBindStats, 9)        // LightGridStats (zeroed each frame, then atomics)
GIB_CONST(uint, kLightGridFlagConeCull, 1)     // LightGridPush.flags: reject spot lights by cone vs cell

struct LightGridStats {
  uint overflowed_cells;     // cells (all cascades) overlapped by more than kLightGridMaxLights lights
  uint max_lights_in_a_cell; // before clamping
  uint pad0, pad1;
};

struct LightGridPush {
  LightGridParams lg;  // x: cascade-0 extent (m), y: cascades, z: light count
  uint flags;          // kLightGridFlagConeCull
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
