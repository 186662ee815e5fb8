// Shared by the calibration kernels (perf/calibrate_fma.comp, calibrate_fma_scalar.comp,
// calibrate_copy.comp, calibrate_dispatch.comp, calibrate_raster.vert/.frag) and perf/calibration.cpp: the device's
// achieved FP32 FMA rate, copy bandwidth and raster fill rate, which the console-scaling model
// divides pass costs by (bench/README.md).
#ifndef GIB_CALIBRATION_SHARED_H
#define GIB_CALIBRATION_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kCalibGroup, 256)
GIB_CONST(uint, kCalibFmaChains, 8)   // independent vec4 FMA chains per thread (latency hiding)
GIB_CONST(uint, kCalibScalarChains, 32)  // calibrate_fma_scalar: independent scalar chains (same 32 FMAs a step)
GIB_CONST(uint, kCalibScalarGroup, 128)
GIB_CONST(uint, kCalibDispatchChain, 64)  // calibrate_dispatch: dispatches timed in one chain
GIB_CONST(uint, kCalibBindOut, 0)     // fma: one float per thread (keeps the chains live)
GIB_CONST(uint, kCalibBindSrc, 0)     // copy: source vec4 buffer
GIB_CONST(uint, kCalibBindDst, 1)     // copy: destination vec4 buffer
struct CalibFmaPush {
  uint iterations;  // loop trips; each trip is kCalibFmaChains x 4 FMAs (8 x 4 x 2 flops)
  float a;          // multiplier and addend from push constants so the compiler cannot fold
  float b;
  uint pad;
};
struct CalibRasterPush {
  uint layers;  // full-screen triangles in the draw, front to back
  uint pad0, pad1, pad2;
};
struct CalibCopyPush {
  uint count;  // vec4 elements
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
