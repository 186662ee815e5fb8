// vrcs_rate: a shading rate (1x1, 2x1, 1x2, 2x2) per 8x8 pixel tile for variable-rate compute
// shading (DOOM: The Dark Ages, "Variable-Rate Compute Shaders", after Fuller 2022). A tile may
// shade coarsely in x when every horizontal pixel pair of a 2x1 cell is alike: last frame's lit
// luminance, tone-mapped l = L / (1 + L), differs by at most `vrcs_threshold`, and (with
// `vrcs_edges`) both pixels show the same instance with normals within 25 degrees (this frame's
// visibility buffer and tangent frame: silhouettes and creases keep full rate). Likewise in y.
// Reads: vbuffer, vis_tangent_frame, last frame's vrcs_luma (deferred_lighting writes it with
// VRCS on: one r32f per pixel, where keeping last frame's RGBA32F lighting cost 4x). Writes: vrcs_rates (tiles per
// rate in its statistics). Frame 0 has no last frame: full rate. `vrcs_force` sets one rate
// everywhere (the negative controls).
// Limits: the luminance is last frame's at the same pixel (no reprojection): under camera
// motion the rate lags by a frame. The seed also weighs the rate by motion and by a per-pass
// sensitivity; ours has one threshold for texturing and lighting.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_vrcs_rate_pass();
uint64_t vrcs_rate_words(uint32_t width, uint32_t height);
}  // namespace gib
