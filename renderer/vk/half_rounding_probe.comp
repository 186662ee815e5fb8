#version 460
#extension GL_GOOGLE_include_directive : require
// The device's packHalf2x16 of every input float (its low half), for the rounding probe in
// renderer/vk/gpu.cpp.
#include "device_spec_shared.h"

layout(local_size_x = kHalfProbeGroup) in;
layout(std430, set = 0, binding = kHalfProbeBindIn) readonly buffer In { float values[]; };
layout(std430, set = 0, binding = kHalfProbeBindOut) writeonly buffer Out { uint halves[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < push.count) halves[i] = packHalf2x16(vec2(values[i], 0.0)) & 0xffffu;
}
