#ifndef GIB_GBUFFER_SHARED_H
#define GIB_GBUFFER_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGbufferGroup, 8)  // 8x8 threads
GIB_CONST(uint, kGbufferBindVbuffer, 8)
GIB_CONST(uint, kGbufferBindAlbedo, 9)    // rgba16f: albedo rgb (decals applied), sheen (cloth; 0: standard BRDF)
GIB_CONST(uint, kGbufferBindNormal, 10)   // rgba16f: shading normal xyz (faces the camera), roughness (the cloth sheen's)
GIB_CONST(uint, kGbufferBindPosition, 11) // rgba32f: world position xyz, w = distance to camera (0: sky)
GIB_CONST(uint, kGbufferBindEmissive, 12) // rgba16f: emitted radiance rgb, translucency
struct GbufferPush {
  uint nan_guards;  // 1: a non-finite or zero shading normal falls back to the face normal
  uint inject_nan;  // 1: write a NaN normal at pixel (inject_x, inject_y) this frame (debug)
  uint inject_x, inject_y;
};
GIB_SHARED_END
#endif
