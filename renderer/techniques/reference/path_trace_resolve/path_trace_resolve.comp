#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/reference/path_trace_resolve/path_trace_resolve_shared.h"

layout(local_size_x = kResolveGroup, local_size_y = kResolveGroup) in;
layout(set = 0, binding = kResolveBindSum, rgba32f) uniform readonly image2D sum_image;
layout(set = 0, binding = kResolveBindOut, rgba32f) uniform writeonly image2D out_image;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_image)))) return;
  vec4 s = imageLoad(sum_image, p);
  imageStore(out_image, p, vec4(s.a > 0.0 ? s.rgb / s.a : vec3(0.0), 1.0));
}
