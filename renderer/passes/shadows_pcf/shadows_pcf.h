// shadows_pcf: the sun's visibility per G-buffer pixel by percentage-closer filtering of the
// cascaded shadow map: `taps` filtered (bilinear) comparisons over a disk of the area-light
// radius (per light: filter_radius, or the sun's angular radius seen from march_distance),
// against the receiver's plane; the tap pattern (a golden-angle disk) turned per pixel. Pixels
// the dilated min/max calls fully lit or shadowed skip the taps. The sun's visibility of every
// technique's shadow_mapped mode (DirectLightingParams::direct_light), and the baseline
// gow-ragnarok's contact hardening is compared with.
// Slots: reads gbuffer_position, gbuffer_normal, shadow_map, shadow_minmax; writes shadow_pcf
// (r32_float, render size).
// Seed: God of War Ragnarök, "Contact Hardening Shadows" (PCF shadows, 1.30 / 0.89 ms at 4K).
// Limits: one blur radius everywhere: too soft at contact, too sharp far from the occluder.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_shadows_pcf_pass();
}
