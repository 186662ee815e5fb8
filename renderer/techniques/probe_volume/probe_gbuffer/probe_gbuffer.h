// probe_gbuffer: the probe G-buffer (AC Shadows RTGI, "Gbuffer update"): for each probe
// probe_select chose to trace (new ones at quarter resolution when quarter_res_new: one ray per
// 2x2 block of texels, written to all four; G-buffer refreshes at full resolution), one ray
// through the centre of each texel of its 20x20 octahedral tile, no jitter (the cached G-buffer
// is relit for many frames), up to trace_range cascade spacings, closest hit with the run's
// alpha strategy. Per texel: albedo and translucency (unorm8), emission (RGB9E5), the normal of
// the side the probe sees (12+12-bit octahedral), sun visibility (one shadow ray to the sun's
// centre, cast from the side facing it; both sides for translucent hits), hit distance (half;
// +Inf on a miss): 14 bytes. Per probe (probe_state): back-face fraction (hits on the back of
// opaque surfaces within one spacing, of all hits), min and max depth; flags traced / quarter.
// Slots: read probe_selection; read_write probe_state, probe_gb_material, probe_gb_normal,
// probe_gb_depth (persistent, probe-major, probe_volume_shared.h).
// Limits: the sun shadow is a hard shadow ray (the seed: a secondary shadow map, rays outside
// it, cloud shadows); it is refreshed only with the G-buffer (the seed's approximation: the sun
// moves little in the ~2 s between refreshes). Materials are the albedo at the hit uv (no
// season LUT, no baked average for complex materials: ours are procedural).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_gbuffer_pass();
}
