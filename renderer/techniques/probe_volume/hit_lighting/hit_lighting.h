// hit_lighting: lights the per-pixel rays (AC Shadows RTGI, "Hit lighting", "Miss lighting",
// "Lighting"). A hit: the sun (a shadow ray; the seed uses its shadow maps), local lights (a
// shadow ray each), both faces of a thin translucent hit, plus albedo x the probes' irradiance
// on both normals, scaled by probe AO when the hit is closer than a probe spacing (probe_ao).
// A miss: the filtered radiance probes at the ray's end when it lies in the volume, else
// nothing. Emission and the sky are the contract's `direct` (direct_lighting's sky rays):
// left out here, so the result is the bounce light only. The ray's irradiance estimate
// pi x L x side weight is encoded as YCoCg SH, order 1 for Y, in 64 bits
// (renderer/codecs/ycocg_sh.h; direction mirrored to the front for back-side rays).
// Slots: read pixel_hits, gbuffer_position, gbuffer_normal, gbuffer_emissive, probe_state,
// probe_irradiance, probe_radiance, probe_visibility; writes pixel_sh (rg32ui).
// Limits: no pre-exposure (the seed scales by last frame's exposure; the codec's per-pixel
// exponent keeps the precision instead); the seed's nearest-probe fast path is shared with
// every probe lookup (nearest_weight).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_hit_lighting_pass();
}
