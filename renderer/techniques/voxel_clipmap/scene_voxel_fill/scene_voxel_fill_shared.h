// scene_voxel_fill <-> C++: bindings, group size, kernels.
#ifndef GIB_SCENE_VOXEL_FILL_SHARED_H
#define GIB_SCENE_VOXEL_FILL_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kScFillGroup, 64)
GIB_CONST(uint, kScFillBindState, 8)      // voxel_clip_state (read_write: stats)
GIB_CONST(uint, kScFillBindVoxels, 9)     // scene_voxel_data (read_write)
GIB_CONST(uint, kScFillBindGeometry, 10)  // voxel_geometry: 3 uints per voxel, max vc_fill_key of the overlapping triangles by dominant normal axis
GIB_CONST(uint, kScFillBindThird, 11)     // scene_voxel_third (write: entered voxels)
GIB_CONST(uint, kScFillSpecKernel, 0)
GIB_CONST(uint, kScFillVoxelize, 0)       // one thread per (triangle, level): mark the entered voxels it overlaps
GIB_CONST(uint, kScFillMerge, 1)          // one thread per voxel: entered voxels take geometry opacity and coarser radiance
struct ScFillPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
