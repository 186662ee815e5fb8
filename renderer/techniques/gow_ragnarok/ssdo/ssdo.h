// ssdo: screen-space directional occlusion (SSDO) of the unshadowed local lights. Per pixel,
// `ssdo_directions` cosine-weighted directions around the normal (a golden-angle pattern turned
// per pixel and frame by a hash) are marched `ssdo_steps` steps to `ssdo_radius` against the
// depth buffer (gbuffer_position); a direction is blocked where a surface lies in front of the
// march point by less than `ssdo_thickness`. Every local light is then lit without a shadow ray
// (the game's lights without shadow maps), Lambertian, scaled by the visibility towards it: the
// open / blocked directions weighted by a lobe around the light's direction. Option ssdo 0:
// every direction open (the unshadowed lights leak: the control).
// Slots: reads gbuffer_position, gbuffer_normal, gbuffer_albedo; writes ssdo_local_light
// (rgba32_float: radiance of the local lights, the `direct` AOV's local-light part) and ssdo_cone
// (rgba16_float: bent normal, open fraction: ambient occlusion, a debug view).
// Seed: God of War Ragnarök, "Light Leaking: SSDO and SSGI" ("SSDO also helps a lot when you have
// unshadowed lights ... We use it to fake shadows on those lights").
// Limits: screen space: what the camera does not see (behind or under furniture seen edge-on,
// off screen) does not occlude; an occluder beyond the light still blocks it; a few directions
// per pixel stand for every light's direction (noisy, no filter); front faces only (no diffuse
// transmission). Culled without local lights, and when direct_lighting shadows them
// (local_shadows 1).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_ssdo_pass();
}
