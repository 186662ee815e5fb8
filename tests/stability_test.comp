#version 460
#extension GL_GOOGLE_include_directive : require
#include "tests/stability_test_shared.h"

layout(local_size_x = kStabilityTestGroup, local_size_y = kStabilityTestGroup) in;
layout(set = 0, binding = kStabilityTestBindSource, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = kStabilityTestBindOut, rgba32f) uniform writeonly image2D out_image;
layout(set = 0, binding = kStabilityTestBindHistory, rgba32f) uniform image2D history;
layout(push_constant) uniform Push { StabilityTestPush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_image)))) return;
  vec4 v = pc.use_source != 0u ? imageLoad(source, p) : vec4(0.25, 0.5, 0.75, 1.0);
  if (pc.frame == pc.bad_frame && p == ivec2(pc.bad_x, pc.bad_y)) v.y = uintBitsToFloat(pc.bad_bits);
  imageStore(out_image, p, v);
  imageStore(history, p, imageLoad(history, p) + v);
}
