#version 460
#extension GL_GOOGLE_include_directive : require
// final_color = direct_light + albedo x gi_irradiance; indirect_diffuse = albedo x gi_irradiance.
#include "renderer/passes/composite/composite_shared.h"

layout(local_size_x = kCompositeGroup, local_size_y = kCompositeGroup) in;
layout(set = 0, binding = kCompositeBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kCompositeBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kCompositeBindIrradiance, rgba32f) uniform readonly image2D gi_irradiance;
layout(set = 0, binding = kCompositeBindColor, rgba32f) uniform writeonly image2D out_color;
layout(set = 0, binding = kCompositeBindIndirect, rgba32f) uniform writeonly image2D out_indirect;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_color)))) return;
  // Sky pixels: albedo and gi_irradiance are 0, so final_color is direct_light's sky radiance.
  vec3 indirect = imageLoad(gb_albedo, p).rgb * imageLoad(gi_irradiance, p).rgb;
  imageStore(out_indirect, p, vec4(indirect, 1.0));
  imageStore(out_color, p, vec4(imageLoad(direct_light, p).rgb + indirect, 1.0));
}
