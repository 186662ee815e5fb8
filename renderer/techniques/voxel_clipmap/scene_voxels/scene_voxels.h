// scene_voxels: the scene-voxel clipmap (Enlisted GDC 2019, "4. Scene representation" and
// Figures 1-2): `levels` nested grids of grid^3 voxels around the camera, the same texel
// dimensions per level and the voxel size doubling per level, all in one buffer (the seed's
// volume atlas), addressed toroidally: when the camera moves, a level's box origin moves
// and only the voxels whose slot now holds a new world cell are cleared (radiance 0, opacity 0,
// flag kVcVoxelNew) for scene_voxel_fill; valid voxels are never copied.
// Slots: read_write voxel_clip_state (box origins, this and last frame), scene_voxel_data.
// Limits: the boxes are centred on the camera, not ahead of it.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_scene_voxels_pass();
}
