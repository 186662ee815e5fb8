// irradiance_select <-> C++: bindings, group size.
#ifndef GIB_IRRADIANCE_SELECT_SHARED_H
#define GIB_IRRADIANCE_SELECT_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kIrrSelectGroup, 256)
GIB_CONST(uint, kIrrSelectBindState, 8)   // voxel_clip_state (read_write: P and its count)
GIB_CONST(uint, kIrrSelectBindVoxels, 9)  // scene_voxel_data (read: which cells hold geometry)
GIB_CONST(uint, kIrrSelectBindCells, 10)  // irradiance_cell_state (read_write: age, flags)
GIB_CONST(uint, kIrrSelectBindQueue, 11)  // irradiance_queue (write)
struct IrrSelectPush {
  VcParams vc;
};
GIB_SHARED_END
#endif
