#ifndef GIB_DIRECT_LIGHTING_SHARED_H
#define GIB_DIRECT_LIGHTING_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kDirectGroup, 8)
GIB_CONST(uint, kDirectBindAlbedo, 8)
GIB_CONST(uint, kDirectBindNormal, 9)
GIB_CONST(uint, kDirectBindPosition, 10)
GIB_CONST(uint, kDirectBindEmissive, 11)
GIB_CONST(uint, kDirectBindOut, 12)  // rgba32f direct radiance (HDR); alpha: the share of the sky rays that met a surface
GIB_CONST(uint, kDirectBindVbuffer, 13)  // triangle ids: the face normal for sky rays
GIB_CONST(uint, kDirectBindSunVisibility, 14)  // r32f sun visibility (DirectLightingParams::sun_visibility)
// Specialization constants: which light types the scene has (dead code elimination).
GIB_CONST(uint, kDirectSpecSun, 0)
GIB_CONST(uint, kDirectSpecSky, 1)
GIB_CONST(uint, kDirectSpecLocal, 2)
GIB_CONST(uint, kDirectSpecAlpha, 3)
GIB_CONST(uint, kDirectSpecEmissive, 4)
GIB_CONST(uint, kDirectSpecSkyUnoccluded, 5)  // the shadow_mapped mode's sky (DirectLightingParams)
struct DirectPush {
  uint sky_rays;    // cosine rays per pixel: sky and emissive surfaces seen from the pixel
  uint nan_guards;  // 1: a non-finite G-buffer normal is replaced by the direction to the camera
  uint pad1, pad2;
};
GIB_SHARED_END
#endif
