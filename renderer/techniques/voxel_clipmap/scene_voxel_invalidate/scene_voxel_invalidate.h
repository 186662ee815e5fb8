// scene_voxel_invalidate: changed geometry (Enlisted GDC 2019, 4.3 "Invalidating/Discarding
// scene representation voxels": "in the simplest scenario (like destruction), we can invalidate
// all voxels in the bounding box of changed geometry (and fill-in data)"). The CPU knows which
// animated or removed (scene key `removed_at`) instances changed since last frame; the union of
// each one's old and new world boxes (up to 4, merged beyond) clears the voxels overlapping it
// to the entered state, so scene_voxel_fill voxelises their triangles again and the feed
// rewrites them without averaging, and the irradiance cells there are aged to the maximum so irradiance_select picks
// them first. invalidate 0 switches it off (the destruction control).
// Slots: read_write voxel_clip_state, scene_voxel_data, irradiance_cell_state.
// Needs: motion (a static scene culls it).
// Limits: the stochastic discard of the seed's slow animations is not done.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_scene_voxel_invalidate_pass();
}
