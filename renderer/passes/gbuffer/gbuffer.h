// gbuffer: attribute interpolation and material evaluation from the visibility buffer.
// For each pixel it re-intersects the camera ray through the pixel centre with the triangle
// the vbuffer names (barycentrics exact in the ray, not perspective-interpolated varyings), and
// the rays through the neighbouring pixel centres with the triangle's plane to get the
// screen-space derivatives of the barycentrics and the UVs; those derivatives box-filter the
// procedural checker so it does not alias. Writes the G-buffer.
// Slots: reads vbuffer; writes gbuffer_albedo, gbuffer_normal, gbuffer_position, gbuffer_emissive.
// Seed: DOOM: The Dark Ages "Visibility Buffer and Deferred Rendering" talk, "Attribute interpolation" (barycentrics and their
// derivatives from the triangle, then deferred texturing).
// Limits: no material classification or per-material dispatch yet (one uber kernel).
// NaN guard (Settings::nan_guards): a non-finite or non-unit shading normal falls back to the face
// normal. Debug: inject_nan 1 writes a NaN normal at (inject_x, inject_y) on frame inject_frame.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gbuffer_pass();
}
