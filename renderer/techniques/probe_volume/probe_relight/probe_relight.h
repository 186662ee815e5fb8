// probe_relight: lighting of the selected probes (AC Shadows RTGI, "Lighting update"). First
// every valid probe not selected this frame is rescaled: its lighting scale follows the ratio
// of the seed's sun + sky estimate now and at its last update (weighted by its sky visibility,
// plus its local-light luminance), so stored radiance tracks a sun or sky change without a
// relight (lighting_scale 0: off, the control). Then each selected probe's G-buffer texels go
// to a hit list and a miss list (entries: selection index << 9 | texel; a quarter-resolution
// probe's 2x2 blocks once) and two indirect dispatches light them:
//   hit: sun (the cached visibility x the current sun), local lights (a shadow ray each), both
//        faces of thin translucent surfaces, plus albedo x last frame's probe irradiance on
//        both normals (multi-bounce; multi_bounce 0: off);
//   miss: the filtered radiance probes at the ray's end when it lies inside the volume (their
//        reflected radiance and sky visibility), else the sky (visibility 1).
// Output per texel: reflected radiance (emission is added by probe_convolve for irradiance
// only, so radiance probes never carry emission or sky that the per-pixel path would count
// twice with direct_lighting's sky rays), sky visibility, and local-light luminance.
// Slots: read probe_selection, probe_gb_material, probe_gb_normal, probe_gb_depth; read_write
// probe_state, probe_irradiance, probe_radiance,
// probe_visibility (read only: last frame's; declared read_write so that the graph orders
// this pass before probe_convolve rewrites them); writes probe_texel_lists (counts,
// indirect arguments, lists),
// probe_texel_radiance, probe_texel_local (per selected probe, transient).
// Limits: local lights are all evaluated (no light grid); shadow rays, not shadow maps.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_relight_pass();
}
