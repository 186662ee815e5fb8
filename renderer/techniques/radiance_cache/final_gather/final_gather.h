// final_gather: the radiance-cache technique's per-pixel irradiance probes. At 1/gather_divisor
// resolution (SizeRule::render for 1, half for 2, quarter for 4) each gather pixel g takes the G-buffer
// sample of its representative full-res pixel g * divisor + divisor / 2 (clamped to the
// render size; the pixel just below and right of the block's centre, shared with gi_denoise
// and gi_upscale) and traces one cosine-distributed ray around its normal (direction: a
// per-pixel R2 sequence over frames, offset by a per-pixel hash). No shading happens here;
// the ray's radiance comes from the first cache that can answer:
//   1. screen: the hit projected with prev_view_proj lands inside last frame's image and is
//      unoccluded there (its clip-space depth matches last frame's gbuffer_position at that
//      pixel within 5%, and the ray hit the camera-facing side): last frame's final_color;
//   2. world: rc_lookup at the hit (a shaded radiance-cache cell);
//   3. irradiance volumes: rc_sample_irradiance at the hit x hit albedo + emission;
//   a miss: the sky.
// The AOV contract (renderer/techniques/aov.h) splits each ray's radiance: the sky where it
// escapes and the emission of the surface it hits reach the gather point with no further
// bounce (`direct`, to gather_direct as RGB, the cosine-sampled estimate of irradiance / pi at
// the gather normal); the rest (the hit's answer minus its emission) bounced there (the SH).
// gi_denoise and gi_upscale filter both parts alike, so `direct` keeps the gather's temporal
// and spatial filtering instead of being traced per pixel by direct_lighting (sky_rays 0; a
// test that sets sky_rays > 0 gets direct_lighting's rays instead and the direct part is 0).
// The radiance goes into 2-band SH per channel: L1 = L Y1(d) pi / cos(theta), the cosine-pdf
// Monte Carlo projection (cos clamped to >= 0.02); L0 is set so that the SH's irradiance / pi at
// the gather normal (gib_sh2_irradiance) is exactly L, the cosine-sampled estimate there (this
// makes L0 = 2 pi Y00 L). The plain projection's L0 = L Y00 pi / cos has infinite variance (a
// grazing ray weighs up to 50x); this one is exact at the gather normal (a flat pixel under a
// constant sky is noise-free), and the L1 band carries the direction for other normals.
// Slots: reads gbuffer_normal, gbuffer_position, rc_cells, probe_irradiance, probe_visibility, exposure,
// read_prev gbuffer_position, read_prev final_color; writes gather_sh_r/g/b (RGBA16F: L0, L1,
// bounce light), gather_direct (RGBA16F: rgb direct part, a 0), gather_hit_distance (R32F: metres, 1000 on a miss, 0 for a sky gather pixel) and
// gather_stats (buffer, uint[4]: rays served by screen, world, volume, sky this frame; cleared
// each frame, diagnostics only: nothing reads it, so it never keeps the pass alive; counted with
// one atomic per subgroup and counter, a ballot's bit count).
// Seed: the idTech 8 "Global Illumination" talk, "Final Gather" (1 ray per pixel, 1/2 or 1/4 res, screen
// -> world -> volumes, 2-band SH in 3 x RGBA16F).
// Limits: the seed's blue noise is an R2 sequence here; gbuffer_albedo (listed in the design's
// slot table) is not read: albedo is applied in composite. The screen cache uses the current
// camera position for its facing test (last frame's is not in the frame constants). Rays leave
// as the reference's paths do: a direction below the face (read from the vbuffer) is mirrored
// above it and the origin offset along the face normal (surface.glsl gib_above_face).
// Pre-exposure: every sample's radiance (sky, screen, world, volumes) is multiplied by P_now,
// word 0 of the `exposure` buffer (exposure.h), before the projection: the SH and gather_direct
// hold radiance x P.
// NaN guard (RcParams.flags.y): a non-finite screen-cache sample is a miss, any other non-finite
// answer is 0, a non-finite normal writes an empty sample. multi_bounce 0: no screen cache.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_final_gather_pass();
}
