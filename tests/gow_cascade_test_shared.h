// tests/gow_cascade_test.comp <-> tests/test_gow_shadows.cpp: the cascade selection and the seam
// blend weight of shadow_cascades.glsl on test points, for comparison with shadow_cascades.h.
#ifndef GIB_GOW_CASCADE_TEST_SHARED_H
#define GIB_GOW_CASCADE_TEST_SHARED_H
#include "shadow_cascades_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGowCascadeTestGroup, 64)
GIB_CONST(uint, kGowCascadeTestBindIn, 0)
GIB_CONST(uint, kGowCascadeTestBindOut, 1)
struct GowCascadeTestPush {  // 128 bytes
  ShadowCascadePush cascades;
  vec4 camera;   // xyz position, w tan(fov_y / 2)
  vec4 forward;  // xyz unit view axis, w aspect
  vec4 sun;      // xyz towards the sun; w unused
};
struct GowCascadeTestIn {
  vec4 x_rel;  // xyz camera-relative point, w margin (m)
};
struct GowCascadeTestOut {
  vec4 result;  // x selected cascade, y blend weight of the next
};
GIB_SHARED_END
#endif
