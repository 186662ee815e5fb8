// ssgi: screen-space one-bounce indirect diffuse, and the frame's sum. Per pixel,
// `ssgi_directions` cosine-weighted directions (the ssdo pattern, its own hash stream) are
// marched `ssgi_steps` steps to `ssgi_radius` against the depth buffer; where one meets a
// surface (in front of the march point by less than `ssgi_thickness`, facing the receiver) it
// gathers that pixel's direct light less its emission: light that bounced once there. The
// receiver reflects albedo x the mean (ssgi_indirect, the `indirect_diffuse` AOV: one bounce,
// from what is on screen). Also writes gow_direct = direct_light + ssdo_local_light (the
// `direct` AOV) and gow_radiance = gow_direct + ssgi_indirect (the technique's output).
// Option ssgi 0: no indirect light.
// Slots: reads gbuffer_position, gbuffer_normal, gbuffer_albedo, gbuffer_emissive,
// direct_light, ssdo_local_light (where the scene has local lights and ssdo lights them);
// writes gow_direct, ssgi_indirect, gow_radiance (rgba32_float).
// Seed: God of War Ragnarök, "Light Leaking: SSDO and SSGI" (SSGI: "extra bounce light"; SSR,
// SSDO and SSGI in one pass, 4.23 ms at 4K on PS5); the bounce from the same frame's direct
// light, so it runs after the lighting.
// Limits: one bounce; misses what is off screen or hidden; a march passing behind a surface
// thinner than ssgi_thickness takes it for a hit (light the sky ray already counted: the
// white-furnace bound watches that); no temporal accumulation (noise at few directions).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_ssgi_pass();
}
