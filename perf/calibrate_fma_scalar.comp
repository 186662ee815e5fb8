#version 460
// A second, differently written FP32 FMA rate kernel, to check the first
// (calibrate_fma.comp) against: scalar floats instead of vec4, kCalibScalarChains independent
// chains, eight steps per loop trip, unrolled, 128-wide groups, the multiplier
// and addend read per chain from push constants. Same flop count per thread and trip (32 FMAs);
// if both reach the same rate, neither is limited by how it was written.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "perf/calibration_shared.h"
layout(local_size_x = kCalibScalarGroup) in;
layout(std430, set = 0, binding = kCalibBindOut) writeonly buffer Out { float outv[]; };
layout(push_constant) uniform Push { CalibFmaPush push; };

void main() {
  uint id = gl_GlobalInvocationID.x;
  float x[kCalibScalarChains];
  for (uint c = 0u; c < kCalibScalarChains; ++c) x[c] = float((id + c * 7u) & 1023u) * 1e-3;
  float a = push.a, b = push.b;
  // Each trip of the outer loop does 8 steps of every chain (fully unrolled: 256 FMAs against
  // one loop test), so one "iteration" is still 32 FMAs per thread as in calibrate_fma.comp
  // (iterations is a multiple of 16).
  uint trips = push.iterations / 8u;
  for (uint i = 0u; i < trips; ++i) {
    [[unroll]] for (uint s = 0u; s < 8u; ++s) {
      [[unroll]] for (uint c = 0u; c < kCalibScalarChains; ++c) x[c] = fma(x[c], a, b);
    }
  }
  float sum = 0.0;
  for (uint c = 0u; c < kCalibScalarChains; ++c) sum += x[c];
  outv[id] = sum;
}
