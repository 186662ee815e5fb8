// gi_upscale: bilateral upscale of the denoised gather SH to full resolution plus the temporal
// filter. For each full-res pixel p: the 4 nearest gather samples (gather pixel g sits at its
// representative full-res pixel g * divisor + divisor / 2) weighted bilinearly x normal x
// plane-depth similarity to p (a 4-tap bilateral; when the bilinear taps all lie on other
// surfaces the most similar tap is taken alone), the SH evaluated with p's full-res normal
// (gib_sh2_irradiance, per channel) -> Curr = irradiance / pi. Temporal filter [Mattauch 2010]:
// New = (n Prev(p_prev) + Curr) / (n + 1), n = min(n + 1, n_max = history_max_frames). Prev is
// the bilinear history around p's world position reprojected with prev_view_proj; each of the 4
// texels is dropped when `disocclusion` is on and its last-frame G-buffer sample fails the
// depth test (distance of p from that sample's tangent plane > 5% of p's depth in last frame's
// view) or the normal test (dot < 0.9); n restarts at 0 when none is left, the reprojection is
// off screen, or on the first frame. The passes after it read the stored (quantised) history
// (gi_irradiance = history / P_now: gi_composite, gi_resolve), so every history_format shows its
// own precision.
// Pre-exposure (exposure.h): the gather SH and the history hold irradiance / pi x P. Prev is
// rescaled by P_now / P_prev (word 0 and 1 of the `exposure` buffer) before the blend, the
// history is stored x P_now, and the readers divide P_now out (absolute units). Every
// threshold here is on weights or geometry, none on values, so P changes none of them.
// The direct part (gi_direct, final_gather.h) takes the same bilateral weights and the same
// temporal filter (its own history, gi_history_direct, in the same format and with the same n),
// without SH evaluation: it is irradiance / pi at the gather normals already.
// Slots: reads gi_sh_r/g/b, gi_direct, gbuffer_normal, gbuffer_position, read_prev gbuffer_position,
// read_prev gbuffer_normal, read_prev gi_history(_direct), read_prev gi_history_frames, exposure; writes
// gi_history and gi_history_direct (persistent ping-pong; history_format 0 RGB9E5 in R32_UINT,
// 1 RGBA16F, 2 R11G11B10F (b10g11r11_float), 3 RGBA32F), gi_history_frames (R32F n, persistent
// ping-pong). It writes no absolute-unit copy of the history (two RGBA32F images, 32 of its 44
// bytes a pixel, were 0.21 of the 1.38 ms it read scaled to a Series S on cornell).
// Seed: the idTech 8 "Global Illumination" talk, "Denoise + Upscale" (bilateral upscale weighted by
// normal/depth, temporal filter with a valid-fragment frame counter, RGB9E5 or RGBA16F history)
// and "RGB9E5 vs R11G11B10F".
// Each 8x8 group first loads every gather sample its taps can reach (geometry, SH, direct part)
// into group-shared memory, once; option upscale_kernel 1 reads each tap from the images instead
// (the same output bit for bit). The reprojection's last-frame texels are read from the images.
// Limits: the seed's 4 poisson taps are the 4 bilinear neighbours here; no history clamping
// (lighting changes fade in over n_max frames); n is interpolated with the history, so it may
// be fractional after camera motion. One kernel per history format (gi_upscale_<format>.comp).
// NaN guard (UpscalePush.nan_guards): non-finite taps, results and history texels are rejected
// (a pixel whose history is all rejected restarts its frame counter).
#pragma once
#include <memory>
#include <string>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gi_upscale_pass();
// The storage format of gi_history for RadianceCacheSettings::history_format (0..3).
Format gi_history_format(uint32_t history_format);
// The kernel `stem` compiled for that history format: "<stem>_rgb9e5.comp", "_rgba16f",
// "_r11g11b10f" or "_rgba32f" (gi_upscale, gi_composite and gi_resolve each have the four).
std::string gi_history_shader(const std::string& stem, uint32_t history_format);
}
