// scene_voxel_invalidate <-> C++: bindings, group size, push constants.
#ifndef GIB_SCENE_VOXEL_INVALIDATE_SHARED_H
#define GIB_SCENE_VOXEL_INVALIDATE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kScInvalidateGroup, 64)
GIB_CONST(uint, kScInvalidateBindState, 8)      // voxel_clip_state (read_write)
GIB_CONST(uint, kScInvalidateBindVoxels, 9)     // scene_voxel_data (read_write)
GIB_CONST(uint, kScInvalidateBindCells, 10)     // irradiance_cell_state (read_write)
GIB_CONST(uint, kScInvalidateMaxBoxes, 4)
struct ScInvalidatePush {
  VcParams vc;
  vec4 box_min[kScInvalidateMaxBoxes];  // world space; w unused
  vec4 box_max[kScInvalidateMaxBoxes];
  uvec4 count;  // x: boxes, y: 1 for voxels, 2 for cells (the kernel's target), z,w unused
};
GIB_SHARED_END
#endif
