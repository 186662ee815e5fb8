#version 460
// Achieved FP32 FMA throughput: kCalibFmaChains independent vec4 fma chains per thread, so
// the loop is bound by FMA issue rate, not by latency, loop overhead or memory. One float out
// per thread.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "perf/calibration_shared.h"
layout(local_size_x = kCalibGroup) in;
layout(std430, set = 0, binding = kCalibBindOut) writeonly buffer Out { float outv[]; };
layout(push_constant) uniform Push { CalibFmaPush push; };

void main() {
  uint id = gl_GlobalInvocationID.x;
  float s = float(id & 255u) * 1e-4;
  vec4 acc[kCalibFmaChains];
  for (uint c = 0u; c < kCalibFmaChains; ++c) acc[c] = vec4(s + float(c), s - float(c), s * 0.5, s + 1.0);
  vec4 a = vec4(push.a), b = vec4(push.b);
  // 8 steps of every chain per loop trip, unrolled (256 FMAs against one loop test: with one
  // step per trip the loop's own instructions held an H100 at 66 % of its FMA rate);
  // iterations is a multiple of 16.
  uint trips = push.iterations / 8u;
  for (uint i = 0u; i < trips; ++i) {
    [[unroll]] for (uint s = 0u; s < 8u; ++s) {
      [[unroll]] for (uint c = 0u; c < kCalibFmaChains; ++c) acc[c] = fma(acc[c], a, b);
    }
  }
  vec4 sum = vec4(0.0);
  for (uint c = 0u; c < kCalibFmaChains; ++c) sum += acc[c];
  outv[id] = sum.x + sum.y + sum.z + sum.w;
}
