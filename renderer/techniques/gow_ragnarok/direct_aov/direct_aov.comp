#version 460
#extension GL_GOOGLE_include_directive : require
// direct_aov: gow_direct = direct_light + ssdo_local_light (see direct_aov.h).
#include "renderer/techniques/gow_ragnarok/direct_aov/direct_aov_shared.h"

layout(constant_id = kDirectAovSpecLocal) const bool kHasLocal = true;
layout(local_size_x = kDirectAovGroup, local_size_y = kDirectAovGroup) in;
layout(set = 0, binding = kDirectAovBindDirect, rgba32f) uniform readonly image2D direct_light;
// Sampled (texelFetch reads any float format): without local lights it holds direct_light, unread.
layout(set = 0, binding = kDirectAovBindLocal) uniform sampler2D local_light;
layout(set = 0, binding = kDirectAovBindOut, rgba32f) uniform writeonly image2D out_direct;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_direct)))) return;
  vec3 direct = imageLoad(direct_light, p).rgb;
  if (kHasLocal) direct += texelFetch(local_light, p, 0).rgb;
  imageStore(out_direct, p, vec4(direct, 1.0));
}
