// screen_trace: the per-pixel rays marched on screen first (AC Shadows RTGI, "Screen tracing"):
// the ray of each ray pixel (include/pv_pixel.glsl) is stepped `screen_steps` times, evenly in
// screen space (1/w and t/w interpolated linearly), up to its range, against the G-buffer's
// distances:
//   - in front of the visible surface: go on (the last such distance is remembered);
//   - behind it by at most `screen_thickness` metres, arriving at its front: a hit on that
//     surface, settled on screen
//     (its material and normal from the G-buffer at the hit pixel, the distance to the
//     surface's plane along the ray);
//   - behind it by more, at its back, off screen, or past the camera plane: "needs world", world_trace
//     traces it in the BVH, whole (screen_resume 1: from the last visible distance, the seed's
//     backtracking, which skips the near wall where a pixel straddles a silhouette and shows
//     the far surface: extreme-range's interior read 1e5x the reference with it);
//   - the whole range in front of the depth buffer: a miss settled on screen.
// A hit or a miss's end whose indoor / outdoor class (the scene's indoor volumes) differs from
// the class of the side the ray leaves is not settled on screen: world_trace traces it. The
// tests above compare with the one surface a pixel's centre shows, wrong where a pixel straddles
// a floor-wall corner (a hit on the floor's plane inside the wall, a point beyond the wall in
// front of the floor's plane), and such points would be lit by the other class's probes
// (extreme-range's closed building: 3.6e3 x the reference; 1.002 with the class test).
// Back-side rays of translucent surfaces skip the march (the seed). screen_steps 0: every ray
// goes to world_trace from min_start. Counts per frame in pixel_trace_stats (valid ray pixels,
// screen hits, screen misses, world rays): stats screen_hit_share, screen_miss_share,
// world_share (the seed's 38% screen only, 49% world, 13% skipped).
// Slots: read gbuffer_position, gbuffer_normal, gbuffer_emissive, gbuffer_albedo, probe_state;
// writes pixel_hits (world_trace completes it) and pixel_trace_stats.
// Limits: linear steps only (no binary search or secant refinement, which the seed added for
// its specular rays); the G-buffer's own albedo is the hit's (decals included), while world
// hits take the material's.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_screen_trace_pass();
}
