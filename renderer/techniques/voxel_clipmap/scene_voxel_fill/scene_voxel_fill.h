// scene_voxel_fill: fills the voxels that entered the clipmap this frame (Enlisted GDC 2019,
// 4.2 "Fill-in new scene representation voxels" and 3.2): their radiance starts from the
// coarser level's voxel holding their centre (when that one was ever fed; the coarsest level
// starts empty), and their opacity from the scene geometry: every triangle is voxelised into
// the entered voxels of each level it overlaps (the talk's "collision models" fill-in, here the
// render triangles themselves), so rays do not pass through walls the camera has not seen. A
// triangle on a voxel boundary fills the voxels on both sides (touching counts, and the voxel
// range starts one below the boundary), so a room's far walls have their inner voxel too.
// Each geometry voxel keeps the triangle it was filled from (the one facing the camera first),
// from which scene_voxel_light lights it while no pixel has fed it. Alpha-tested materials give their baked mean opacity
// when semi_transparent is on. geometry_fill 0 (the control) leaves entered voxels empty.
// Slots: read_write voxel_clip_state, scene_voxel_data; writes voxel_geometry (transient).
// Limits: triangles are tested against each level's whole box when any of its voxels entered
// (one thread per triangle and level; no spatial culling of triangles).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_scene_voxel_fill_pass();
}
