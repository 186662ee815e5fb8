// scene_voxel_feed: updates the scene voxels from the G-buffer (Enlisted GDC 2019, 4.1): each
// frame feed_pixels (K) pixels are chosen at random (seeded by frame and sample); sky pixels
// and pixels of moving objects (animated instances, up to 8) are skipped; each is lit as the
// voxel will send light on: direct_light (emission, sun, local lights) plus albedo x the
// irradiance clipmap at the pixel (bounce, and sky when direct_lighting traces no sky rays),
// which closes the loop to multiple bounces (multi_bounce 0: the bounce part left out, a control); and averaged exponentially (feed_weight) into its
// voxel in every level whose box holds it. A voxel never fed is written without averaging.
// Opacity: 1 for opaque pixels; with semi_transparent, an alpha-tested material's mean opacity,
// and a semi-transparent pixel leaves a voxel that opaque pixels fed at its opacity (4.4).
// Several samples in one voxel: the one with the largest id writes it (an atomicMax claim, then
// the write), so the result does not depend on thread order (the seed ignores the overwrite);
// only owners light their pixel. Stores round stochastically (gib_pack_rgb9e5_dither): rounded
// to nearest, a blend moving by less than half a unit a frame stops short of its limit.
// Slots: read vbuffer, gbuffer_albedo, gbuffer_normal, gbuffer_position, direct_light,
// irradiance_x/_y/_z, irradiance_cell_state; read_write voxel_clip_state, scene_voxel_data;
// writes voxel_feed_owner (transient).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_scene_voxel_feed_pass();
}
