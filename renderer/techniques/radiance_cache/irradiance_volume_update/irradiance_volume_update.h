// irradiance_volume_update: convolves the updated cascade's probe rays into its octahedral
// irradiance and visibility tiles (the idTech 8 "Global Illumination" talk,
// "Irradiance Volumes Update": one dispatch, 8x8 groups, radiance-cache results (sky on a miss)
// into group-shared memory, irradiance per texel [Greger 1998], previous frame added, RGB9E5 +
// RG16F tiles of 8x8 with a 1-texel border in a 2560-wide atlas, DDGI-like [Majercik 2019]).
// First the whole atlas is copied from last frame (both images: cascades not updated keep
// their tiles), then one 8x8 group per probe of cascade frame % cascades:
//   load   each thread takes rays tid, tid + 64, ...: a miss -> sky radiance; a hit at
//          p = probe + dir * distance -> rc_lookup(p) (the cell shaded this frame or reused);
//          a hit whose cell was dropped -> emission + albedo x last frame's volumes at the hit
//          (rc_sample_irradiance; 0 where no probe around it was updated yet)
//   texel  n = direction of the thread's texel; irradiance / pi = sum L_i max(0, n.d_i) /
//          sum max(0, n.d_i) (a ratio estimator: exact for uniform radiance at any ray count;
//          the plain Monte Carlo form (4 / N) sum L_i max(0, n.d_i) has the same expectation
//          since E[max(0, n.d)] = 1/4 for uniform d); moments (mean, mean square of the
//          distance clamped to min(4 x spacing, 200 m)) weighted by max(0, n.d)^16
//   blend  with last frame's texel by probe_hysteresis, except on a probe's first update
//          (last frame's mean distance is 0 only before that)
//   store  RGB9E5 (packing.glsl) and RG16F, then the 36 border texels (gib_oct_border_source).
// Slots: reads probe_hits, rc_cells, read_prev probe_irradiance/probe_visibility; writes
// probe_irradiance (r32_uint, 2560 x 160 * cascades, persistent) and probe_visibility (rg16f).
// Limits: at most 256 rays per probe; a probe slot that scrolls to a new position (camera moved
// a whole cell) blends with the tile of the probe that left (no per-probe age); the fallback for
// dropped cells lacks direct light at the hit.
// NaN guard (RcParams.flags.y): non-finite rays are dropped, a non-finite previous visibility
// texel is not blended. multi_bounce 0: the dropped-cell fallback returns only emission.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_irradiance_volume_update_pass();
}
