#version 460
// Achieved FP32 FMA throughput: kCalibFmaChains independent vec4 fma chains per thread, so
// the loop is bound by FMA issue rate, not by latency or memory. One float out per thread.
#extension GL_GOOGLE_include_directive : require
#include "bench/calibration_shared.h"
layout(local_size_x = kCalibGroup) in;
layout(std430, set = 0, binding = kCalibBindOut) writeonly buffer Out { float outv[]; };
layout(push_constant) uniform Push { CalibFmaPush push; };

void main() {
  uint id = gl_GlobalInvocationID.x;
  float s = float(id & 255u) * 1e-4;
  vec4 acc[kCalibFmaChains];
  for (uint c = 0u; c < kCalibFmaChains; ++c) acc[c] = vec4(s + float(c), s - float(c), s * 0.5, s + 1.0);
  vec4 a = vec4(push.a), b = vec4(push.b);
  for (uint i = 0u; i < push.iterations; ++i) {
    for (uint c = 0u; c < kCalibFmaChains; ++c) acc[c] = fma(acc[c], a, b);
  }
  vec4 sum = vec4(0.0);
  for (uint c = 0u; c < kCalibFmaChains; ++c) sum += acc[c];
  outv[id] = sum.x + sum.y + sum.z + sum.w;
}
