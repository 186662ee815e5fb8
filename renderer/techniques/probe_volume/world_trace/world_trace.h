// world_trace: the per-pixel rays screen_trace could not settle, through the BVH (AC Shadows
// RTGI, "World tracing"): from the distance screen_trace left them at (the last point seen in
// front of the depth buffer; min_start, default 0, for back-side rays; the seed's 0.05 m tunnels
// through the wall beside a corner) to
// pixel_range x the probe trace range of the cascade around the origin, closest hit with the
// run's alpha strategy. The ray is rebuilt from its seed (include/pv_pixel.glsl: one cosine ray
// per ray pixel, 1/2 resolution by default, the seed's quarter; the side of a translucent
// surface chosen with probability t / (1 + t)).
// Completes pixel_hits (rgba32ui, probe_volume_shared.h): the hit's packed material (albedo rgb
// + translucency unorm8), its normal on the side the ray sees (oct 16+16), the hit distance
// (the range on a miss) and flags.
// Slots: read gbuffer_position, gbuffer_normal, gbuffer_emissive, probe_state; read_write
// pixel_hits (screen_trace writes it).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_world_trace_pass();
}
