// tests/gow_ss_test.comp <-> tests/test_gow_ssdo.cpp.
#ifndef GIB_GOW_SS_TEST_SHARED_H
#define GIB_GOW_SS_TEST_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGowSsTestGroup, 64)
GIB_CONST(uint, kGowSsTestBindIn, 0)
GIB_CONST(uint, kGowSsTestBindOut, 1)
struct GowSsTestIn {
  uvec4 key;     // seed, frame, pixel x, pixel y
  uvec4 index;   // stream, direction i, directions n, unused
  vec4 normal;   // xyz unit
};
struct GowSsTestOut {
  vec4 rotation;   // xy: turn, jitter
  vec4 direction;  // xyz
};
GIB_SHARED_END
#endif
