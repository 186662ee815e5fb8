// The common head of shadows_pcf.comp and shadows_contact_hardening.comp: bindings (the
// shadow-map atlas, its dilated min/max, the G-buffer, the visibility output) and includes.
// The includer includes its <pass>_shared.h first.
#include "frame.glsl"
#include "hash.glsl"
layout(local_size_x = kShadowGroup, local_size_y = kShadowGroup) in;
// The atlas as a sampled image: csm_shadow_tap2 gathers a tap's four texels in one load.
layout(set = 0, binding = kShadowBindMap) uniform sampler2D shadow_map;
layout(set = 0, binding = kShadowBindMinMax, rg32f) uniform readonly image2D shadow_minmax;
layout(set = 0, binding = kShadowBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kShadowBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kShadowBindOut, r32f) uniform writeonly image2D out_visibility;
layout(push_constant) uniform Push { ShadowCascadePush push; };
#define CSM_SHADOW_MAP_BOUND 1
#include "shadow_cascades.glsl"
#include "shadow_receiver.glsl"
