// pixel_upscale: the per-pixel GI at full resolution (AC Shadows RTGI, "Upscaling": bilateral
// on depth, normal and material; the SH evaluated per pixel with the high-resolution normal).
// Each pixel takes the 4 nearest ray pixels (bilinear weights) times the seed's depth weight
// 1 / (0.1 + |dz|)^2 times pixel_denoise's bilateral (plane, normal, material class), and
// evaluates each one's SH for its own normal (include/pv_pixel.glsl, pv_eval_irradiance).
// Output: gi_irradiance (irradiance / pi of bounce light, composite's input) and
// gi_direct_irradiance = 0 (the sky and emissive surfaces are direct_lighting's: its sky rays).
// Slots: read pixel_gi_y, pixel_gi_c, gbuffer_position, gbuffer_normal, gbuffer_emissive;
// writes gi_irradiance, gi_direct_irradiance (rgba32f).
// Limits: a pixel whose 4 taps all lie on other surfaces falls back to the depth weight only.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_pixel_upscale_pass();
}
