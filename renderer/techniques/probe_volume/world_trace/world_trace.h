// world_trace: the per-pixel rays through the BVH (AC Shadows RTGI, "World tracing"): one
// cosine-distributed ray per ray pixel (1/2 resolution by default: the seed's quarter
// resolution; pixel_divisor 1: full) from the G-buffer surface of its source pixel
// (renderer/techniques/probe_volume/include/pv_pixel.glsl: the pixel of its 2x2 block rotating
// over frames, the side of a translucent surface chosen with probability t / (1 + t)), from
// 0.05 m (the seed's minimum start distance) to pixel_range x the probe trace range of the
// cascade around it, closest hit with the run's alpha strategy.
// Output (pixel_hits, rgba32ui): the hit's packed material (albedo rgb + translucency unorm8),
// its normal on the side the ray sees (oct 16+16), the hit distance (the range on a miss) and
// flags (valid, hit, back side); the ray itself is rebuilt from the same seed downstream.
// Slots: read gbuffer_position, gbuffer_normal, gbuffer_emissive, probe_state; writes pixel_hits.
// Limits: every ray is traced in the BVH: the screen-space march that the seed runs first
// (screen_trace: 87% of its rays resolved or shortened on screen) is not built yet.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_world_trace_pass();
}
