#version 460
// Dispatch latency: one workgroup that does nothing but keep its one store conditional, so the
// dispatch is launched, runs and drains with no work (perf/calibration.cpp times a chain of them,
// each behind a compute -> compute barrier, as a pass's dispatches run in a frame).
#extension GL_GOOGLE_include_directive : require
#include "perf/calibration_shared.h"
layout(local_size_x = kCalibGroup) in;
layout(std430, set = 0, binding = kCalibBindOut) writeonly buffer Out { float outv[]; };
layout(push_constant) uniform Push { CalibFmaPush push; };

void main() {
  if (gl_GlobalInvocationID.x == push.iterations) outv[0] = push.a;  // iterations: never a thread id
}
