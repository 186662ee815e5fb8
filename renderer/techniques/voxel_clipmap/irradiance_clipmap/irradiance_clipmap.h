// irradiance_clipmap: the irradiance map (Enlisted GDC 2019, 3 and 3.1-3.2, Figure 1): nested
// grids of ambient cubes around the camera, (grid / 2)^3 cells per level, cell size twice the
// level's voxel size, six directions stored as three buffers of +/- pairs (irradiance_x / _y /
// _z; the seed's 3 textures), each direction's bounce light (voxel hits) and sky light (ray
// misses) apart. Addressed toroidally like the voxels: when a level's box moves, the cells that
// entered it start from the coarser level's cell holding their centre (3.2: "for each of the
// finer grid levels we initialize cells from a coarser level"; the coarsest starts empty) with
// the largest age, so irradiance_select relights them soon.
// Slots: read_write voxel_clip_state, irradiance_x, irradiance_y, irradiance_z,
// irradiance_cell_state.
// Limits: a coarser cell that entered in the same frame is not copied (its value is not yet
// known); the hardware trilinear filtering of the seed's volume textures is done by hand
// (irradiance_shade), as the cubes live in buffers.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_irradiance_clipmap_pass();
}
