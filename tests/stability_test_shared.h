// tests/test_stability.cpp's injection kernel: writes a known value everywhere and one bad
// value at (bad_x, bad_y) on frame bad_frame, and accumulates into a persistent history.
#ifndef GIB_STABILITY_TEST_SHARED_H
#define GIB_STABILITY_TEST_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kStabilityTestGroup, 8)
GIB_CONST(uint, kStabilityTestBindSource, 0)   // rgba32f: read when use_source != 0
GIB_CONST(uint, kStabilityTestBindOut, 1)      // rgba32f: written
GIB_CONST(uint, kStabilityTestBindHistory, 2)  // rgba32f: history += written value
struct StabilityTestPush {
  uint frame, bad_frame, bad_x, bad_y;
  uint bad_bits;    // float bits stored into channel 1 of the bad texel
  uint use_source;  // 0: the value is (0.25, 0.5, 0.75, 1); 1: the source texel
  uint pad0, pad1;
};
GIB_SHARED_END
#endif
