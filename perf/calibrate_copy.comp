#version 460
// Achieved memory bandwidth: a grid-stride vec4 copy between two buffers much larger than the
// device's last-level cache; bytes moved = 2 x buffer size (one read, one write).
#extension GL_GOOGLE_include_directive : require
#include "perf/calibration_shared.h"
layout(local_size_x = kCalibGroup) in;
layout(std430, set = 0, binding = kCalibBindSrc) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = kCalibBindDst) writeonly buffer Dst { vec4 dst[]; };
layout(push_constant) uniform Push { CalibCopyPush push; };

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < push.count; i += stride) dst[i] = src[i];
}
