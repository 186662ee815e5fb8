// scene_voxel_light <-> C++: bindings, group size, specialisation constants.
#ifndef GIB_SCENE_VOXEL_LIGHT_SHARED_H
#define GIB_SCENE_VOXEL_LIGHT_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kScLightGroup, 64)
GIB_CONST(uint, kScLightBindState, 8)    // voxel_clip_state (read)
GIB_CONST(uint, kScLightBindVoxels, 9)   // scene_voxel_data (read_write)
GIB_CONST(uint, kScLightBindX, 10)       // irradiance_x (read)
GIB_CONST(uint, kScLightBindY, 11)
GIB_CONST(uint, kScLightBindZ, 12)
GIB_CONST(uint, kScLightBindCells, 13)   // irradiance_cell_state (read)
GIB_CONST(uint, kScLightBindThird, 14)  // scene_voxel_third (read: the wall test's third planes)
GIB_CONST(uint, kScLightBindVis, 15)    // irradiance_cell_vis (read: the cells' flood masks)
GIB_CONST(uint, kScLightSpecAlpha, 0)    // the scene has alpha-tested materials (bvh_alpha.glsl)
GIB_CONST(uint, kScLightSpecSun, 1)
GIB_CONST(uint, kScLightSpecLocal, 2)
struct ScLightPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
