// gi_denoise: spatial denoise of the final gather's SH at gather resolution: a separable
// "bilateral" gaussian, horizontal (gather_sh_* -> gi_denoise_tmp_*) then vertical
// (gi_denoise_tmp_* -> gi_sh_*), 2 * denoise_radius + 1 taps each. A tap's weight is the
// gaussian (sigma = radius / 2) times edge stops on the normal (pow(max(0, dot), 32)), the
// depth (distance from the centre's tangent plane relative to its view distance, e^(-rel/0.02))
// and, only with the option denoise_hit_weight 1 (the seed's; default 0, it biases the mean:
// radiance_cache.md), the gather hit-distance delta of the SH taps (relative, e^(-dh^2): a hit at
// 1 m vs 3 m keeps 0.64, a hit vs a miss 0.37); constants
// and formulas in gi_denoise_shared.h. A gather pixel's geometry is the G-buffer sample of its representative
// full-res pixel g * divisor + divisor / 2 (final_gather's convention). Sky gather pixels are
// skipped as taps and written as 0.
// Slots: reads gather_sh_r/g/b, gather_direct, gather_hit_distance, gbuffer_normal,
// gbuffer_position; writes gi_denoise_tmp_r/g/b/direct (horizontal result), gi_sh_r/g/b and
// gi_direct (RGBA16F, gather resolution). The direct part (final_gather.h, the AOV contract)
// always takes the geometry weights only.
// Seed: the idTech 8 "Global Illumination" talk, "Denoise + Upscale" (spatial denoise at final-gather
// resolution, separable bilateral gaussian weighted by normal/depth and hit-distance deltas).
// Departure: the hit-distance weight is off by default (see above).
// Group-shared preload (the seed's "pre-load to group shared memory"): each 8x8 group loads its
// tile (the group widened by the radius either side along the axis) once, and every tap reads it
// there, where the radius fits the tile (<= kDenoiseTileMaxRadius, 8); option denoise_kernel 1 (and a
// larger radius) reads each tap from the images. Both give the same output bit for bit.
// The tile keeps the FP16 values (normal, SH, direct part) as FP16, as the seed's, and the
// position and hit distance as fp32: 60 B a texel.
// Limits: the vertical pass weighs hit distances of the unfiltered gather, as the horizontal one does.
// radius 0 copies.
// NaN guard (DenoisePush.nan_guards): taps with a non-finite weight or SH are skipped.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gi_denoise_pass();
}
