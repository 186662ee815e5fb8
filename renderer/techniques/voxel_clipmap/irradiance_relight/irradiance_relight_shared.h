// irradiance_relight <-> C++: bindings, specialisation constants.
#ifndef GIB_IRRADIANCE_RELIGHT_SHARED_H
#define GIB_IRRADIANCE_RELIGHT_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kIrrRelightBindState, 8)    // voxel_clip_state (read)
GIB_CONST(uint, kIrrRelightBindVoxels, 9)   // scene_voxel_data (read)
GIB_CONST(uint, kIrrRelightBindQueue, 10)   // irradiance_queue (read; indirect arguments)
GIB_CONST(uint, kIrrRelightBindX, 11)       // irradiance_x (read_write)
GIB_CONST(uint, kIrrRelightBindY, 12)
GIB_CONST(uint, kIrrRelightBindZ, 13)
GIB_CONST(uint, kIrrRelightBindCells, 14)   // irradiance_cell_state (read_write)
GIB_CONST(uint, kIrrRelightBindVis, 15)     // irradiance_cell_vis (write: the cell's flood mask)
GIB_CONST(uint, kIrrRelightSpecRays, 0)     // workgroup size: one thread per ray
struct IrrRelightPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
