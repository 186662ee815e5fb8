// radiance_cache_shade: shades every cell radiance_cache_update queued this frame (seed
// the idTech 8 "Global Illumination" talk, "World Radiance Cache Update": indirect
// dispatch from the active-cell counter, the hit record rebuilt into surface inputs, the raster
// lighting loop, previous-frame irradiance volumes for multiple bounces, reuse for N frames).
// One thread per rc_active entry (indirect dispatch, args in rc_counters). The surface comes from
// the cell's hit record (triangle + barycentrics through surface.glsl), seen from the side the
// probe ray arrived on. Outgoing diffuse radiance (Lambertian, translucency transmits light
// from the back face as in direct_lighting) =
//   emission
//   + sun: one shadow ray into the sun's cone
//   + local lights: those of the light-grid cell holding the point (light_grid.glsl), one shadow
//     ray each (only when the scene has local lights: specialization constant, slot declared)
//   + sky and bounce: one cosine-distributed ray; a miss returns the sky radiance; a hit q returns
//     the radiance leaving q: the cache cell of q when it was shaded in an earlier frame, else
//     emission_q + albedo_q x last frame's irradiance volumes at q (rc_sample_irradiance). This
//     is the multi-bounce path; the volumes are not also added at the point itself, which would
//     count the sky twice.
// Stored as RGB9E5 in RcCell.radiance; shaded_frame = frame + 1.
// Slots: reads probe_hits, rc_active, rc_counters, light_grid (local lights only), read_prev
// probe_irradiance/probe_visibility; read_write rc_cells.
// Limits: one sample per light type per shade (a cell is then reused cache_reuse_frames frames,
// no temporal blend of cell radiance); the bounce fallback misses the direct light at q; light
// grid cells cap at 64 lights.
// NaN guard (RcParams.flags.y): a non-finite result leaves the cell unshaded (shaded_frame 0).
// multi_bounce 0 (RcParams.flags.z): the bounce ray returns only the emission at its hit. Debug:
// inject_nan 2 (RcShadePush.inject). Details: renderer/techniques/radiance_cache/radiance_cache.md.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_radiance_cache_shade_pass();
}
