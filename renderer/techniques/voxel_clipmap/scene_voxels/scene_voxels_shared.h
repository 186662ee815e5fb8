// scene_voxels <-> C++: bindings, group size, kernels.
#ifndef GIB_SCENE_VOXELS_SHARED_H
#define GIB_SCENE_VOXELS_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kScVoxelsGroup, 64)
GIB_CONST(uint, kScVoxelsBindState, 8)   // voxel_clip_state (read_write)
GIB_CONST(uint, kScVoxelsBindVoxels, 9)  // scene_voxel_data (read_write)
GIB_CONST(uint, kScVoxelsSpecKernel, 0)
GIB_CONST(uint, kScVoxelsOrigins, 0)     // one group: every level's box around the camera
GIB_CONST(uint, kScVoxelsScroll, 1)      // one thread per voxel: voxels that entered a box are cleared
struct ScVoxelsPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
