// irradiance_shade <-> C++: bindings, group size.
#ifndef GIB_IRRADIANCE_SHADE_SHARED_H
#define GIB_IRRADIANCE_SHADE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kIrrShadeGroup, 8)  // 8x8 threads
GIB_CONST(uint, kIrrShadeBindState, 8)
GIB_CONST(uint, kIrrShadeBindX, 9)
GIB_CONST(uint, kIrrShadeBindY, 10)
GIB_CONST(uint, kIrrShadeBindZ, 11)
GIB_CONST(uint, kIrrShadeBindCells, 12)
GIB_CONST(uint, kIrrShadeBindNormal, 13)
GIB_CONST(uint, kIrrShadeBindPosition, 14)
GIB_CONST(uint, kIrrShadeBindBounce, 15)   // gi_irradiance (rgba32f, irradiance / pi)
GIB_CONST(uint, kIrrShadeBindSky, 16)      // gi_direct_irradiance (rgba32f, irradiance / pi)
GIB_CONST(uint, kIrrShadeBindVoxels, 17)   // scene_voxel_data (read: walls between a pixel and a cell)
GIB_CONST(uint, kIrrShadeBindDirect, 18)   // direct_light (alpha: the pixel's share of sky rays that met a surface)
GIB_CONST(uint, kIrrShadeBindThird, 19)  // scene_voxel_third (read: the wall test's third planes)
GIB_CONST(uint, kIrrShadeBindVis, 20)    // irradiance_cell_vis (read: the cells' flood masks)
struct IrrShadePush {
  VcParams vc;
};
GIB_SHARED_END
#endif
