#ifndef GIB_ATTRIBUTE_INTERPOLATE_SHARED_H
#define GIB_ATTRIBUTE_INTERPOLATE_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kAttrGroup, 8)
GIB_CONST(uint, kAttrBindVbuffer, 8)
GIB_CONST(uint, kAttrBindBary, 9)          // rg16f: barycentrics (b, c) of the pixel centre
GIB_CONST(uint, kAttrBindBaryDeriv, 10)    // rgba16ui: packed ddx, ddy of (b, c) + 4 flags
GIB_CONST(uint, kAttrBindTangentFrame, 11) // rgba16f: world normal xy, world tangent xy
struct AttrPush {
  uint nan_guards;  // 1: a non-finite or non-unit shading normal falls back to the face normal
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
