// scene_voxel_feed <-> C++: bindings, group size, kernels, push constants.
#ifndef GIB_SCENE_VOXEL_FEED_SHARED_H
#define GIB_SCENE_VOXEL_FEED_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kScFeedGroup, 64)
GIB_CONST(uint, kScFeedBindState, 8)      // voxel_clip_state (read_write: stats)
GIB_CONST(uint, kScFeedBindVoxels, 9)     // scene_voxel_data (read_write)
GIB_CONST(uint, kScFeedBindOwner, 10)     // voxel_feed_owner: uint per voxel, the sample that writes it
GIB_CONST(uint, kScFeedBindX, 11)         // irradiance_x (read)
GIB_CONST(uint, kScFeedBindY, 12)
GIB_CONST(uint, kScFeedBindZ, 13)
GIB_CONST(uint, kScFeedBindCells, 14)     // irradiance_cell_state (read)
GIB_CONST(uint, kScFeedBindVbuffer, 15)
GIB_CONST(uint, kScFeedBindAlbedo, 16)
GIB_CONST(uint, kScFeedBindNormal, 17)
GIB_CONST(uint, kScFeedBindPosition, 18)
GIB_CONST(uint, kScFeedBindDirect, 19)    // direct_light
GIB_CONST(uint, kScFeedBindEmissive, 20)  // gbuffer_emissive
GIB_CONST(uint, kScFeedBindThird, 21)  // scene_voxel_third (read: the wall test's third planes)
GIB_CONST(uint, kScFeedBindVis, 22)    // irradiance_cell_vis (read: the cells' flood masks)
GIB_CONST(uint, kScFeedSpecKernel, 0)
GIB_CONST(uint, kScFeedClaim, 0)          // one thread per sample: atomicMax of its id into each voxel it falls in
GIB_CONST(uint, kScFeedWrite, 1)          // one thread per sample: the owner lights its pixel and writes the voxels
GIB_CONST(uint, kScFeedMaxMoving, 8)      // moving instances whose pixels are skipped
struct ScFeedPush {
  VcParams vc;
  uvec4 moving[2];  // instance ids of animated instances (0xffffffff: none)
};
GIB_SHARED_END
#endif
