// scene_voxel_light: lights the voxels no pixel has fed from the triangle they were filled from
// (Enlisted GDC 2019, 4.2: "if we can use any kind of actual rendering models ... we will be
// able to fill in scene voxels with good and correctly lit (correct materials) data"). Each
// frame it visits lit_voxels voxels of the atlas, a window that moves on by as many every frame
// (at the presets one level's worth: every voxel once every `levels` frames). A visited voxel
// with geometry opacity that no G-buffer pixel has fed is lit at the point of its triangle
// (scene_voxel_fill's key, the face towards the camera first) nearest its centre (moved a
// tenth of a voxel towards the centroid, off the triangle's edges): the sun and
// local lights with a shadow ray each, emission, and albedo x the irradiance clipmap there
// (bounce and direct parts: sky and emitters reach it through the cubes, as with sky_rays 0).
// The value is written without averaging: it has no noise of its own (one fixed point; the
// cubes average over time). So walls the camera never sees keep sending their light and take
// part in every bounce; a static camera in a closed room converges. Pixel-fed voxels are left
// to the feed (textures, exact sky rays). The radiance is stored with stochastic rounding (a
// voxel re-lit to the same value would round the same way each time: a bias the loop
// multiplies). With geometry_light 0 the pass declares itself switched off and the graph
// culls it.
// Slots: read irradiance_x/_y/_z, irradiance_cell_state; read_write voxel_clip_state,
// scene_voxel_data.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_scene_voxel_light_pass();
}
