#version 460
#extension GL_GOOGLE_include_directive : require
// The AOV contract (renderer/techniques/aov.h): direct_radiance = direct_light (emission, sun,
// local lights) + albedo x gi_direct_irradiance (sky and emissive surfaces reached by the
// gather with no further bounce); indirect_diffuse = albedo x gi_irradiance (bounce light);
// final_color = direct_radiance + indirect_diffuse.
#include "renderer/passes/composite/composite_shared.h"

layout(local_size_x = kCompositeGroup, local_size_y = kCompositeGroup) in;
layout(set = 0, binding = kCompositeBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kCompositeBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kCompositeBindIrradiance, rgba32f) uniform readonly image2D gi_irradiance;
layout(set = 0, binding = kCompositeBindColor, rgba32f) uniform writeonly image2D out_color;
layout(set = 0, binding = kCompositeBindIndirect, rgba32f) uniform writeonly image2D out_indirect;
layout(set = 0, binding = kCompositeBindGiDirect, rgba32f) uniform readonly image2D gi_direct;
layout(set = 0, binding = kCompositeBindDirectOut, rgba32f) uniform writeonly image2D out_direct;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_color)))) return;
  // Sky pixels: albedo and gi_irradiance are 0, so final_color is direct_light's sky radiance.
  vec3 albedo = imageLoad(gb_albedo, p).rgb;
  vec3 indirect = albedo * imageLoad(gi_irradiance, p).rgb;
  vec3 direct = imageLoad(direct_light, p).rgb + albedo * imageLoad(gi_direct, p).rgb;
  imageStore(out_indirect, p, vec4(indirect, 1.0));
  imageStore(out_direct, p, vec4(direct, 1.0));
  imageStore(out_color, p, vec4(direct + indirect, 1.0));
}
