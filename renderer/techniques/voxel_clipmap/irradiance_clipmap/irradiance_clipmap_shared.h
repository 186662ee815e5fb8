// irradiance_clipmap <-> C++: bindings, group size, kernels.
#ifndef GIB_IRRADIANCE_CLIPMAP_SHARED_H
#define GIB_IRRADIANCE_CLIPMAP_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kIrrClipmapGroup, 64)
GIB_CONST(uint, kIrrClipmapBindState, 8)   // voxel_clip_state (read_write)
GIB_CONST(uint, kIrrClipmapBindX, 9)       // irradiance_x (read_write)
GIB_CONST(uint, kIrrClipmapBindY, 10)      // irradiance_y
GIB_CONST(uint, kIrrClipmapBindZ, 11)      // irradiance_z
GIB_CONST(uint, kIrrClipmapBindCells, 12)  // irradiance_cell_state
GIB_CONST(uint, kIrrClipmapSpecKernel, 0)
GIB_CONST(uint, kIrrClipmapOrigins, 0)     // one group: every level's cell box around the camera
GIB_CONST(uint, kIrrClipmapScroll, 1)      // one thread per cell: cells that entered start from the coarser level
struct IrrClipmapPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
