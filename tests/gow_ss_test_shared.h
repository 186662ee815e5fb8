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
  uvec4 index;   // stream, direction i, directions n, surface pixel (0..3)
  vec4 normal;   // xyz unit
  vec4 surface;  // xyz: a normal to encode (unit, or broken: NaN, zero), w: distance
};
struct GowSsTestOut {
  vec4 rotation;   // xy: turn, jitter
  vec4 direction;  // xyz
  uvec4 packed;    // xy: gow_ss_pack_surface; decoded: z the pixel, w 1 where the normal is usable
  vec4 unpacked;   // xyz: the decoded normal, w: the decoded distance
};
GIB_SHARED_END
#endif
