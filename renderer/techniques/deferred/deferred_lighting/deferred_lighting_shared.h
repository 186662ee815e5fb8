#ifndef GIB_DEFERRED_LIGHTING_SHARED_H
#define GIB_DEFERRED_LIGHTING_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kLightBindAlbedo, 8)
GIB_CONST(uint, kLightBindNormal, 9)
GIB_CONST(uint, kLightBindPosition, 10)
GIB_CONST(uint, kLightBindEmissive, 11)
GIB_CONST(uint, kLightBindOut, 12)       // rgba32f direct radiance (HDR)
GIB_CONST(uint, kLightBindVbuffer, 13)
GIB_CONST(uint, kLightBindWorkloads, 14) // tile_workloads (classified kernels only)
GIB_CONST(uint, kLightBindRates, 15)     // vrcs_rates (VRCS kernels only)
GIB_CONST(uint, kLightBindLuma, 16)      // vrcs_luma: r32f tone-mapped luminance for vrcs_rate (VRCS kernels only)
GIB_CONST(uint, kLightBindSunVisibility, 17)  // r32f sun visibility (shadow_mapped kernels only)
// Specialization constants: the scene's lights (as direct_lighting) and the workload.
GIB_CONST(uint, kLightSpecSun, 0)
GIB_CONST(uint, kLightSpecSky, 1)
GIB_CONST(uint, kLightSpecLocal, 2)
GIB_CONST(uint, kLightSpecAlpha, 3)
GIB_CONST(uint, kLightSpecEmissive, 4)
GIB_CONST(uint, kLightSpecWorkload, 5)  // kWorkload* (classified kernel)
GIB_CONST(uint, kLightSpecSkyUnoccluded, 6)  // the shadow_mapped mode's sky (DirectLightingParams)
struct LightPush {
  uint sky_rays;
  uint nan_guards;
  uint tiles_x;
  uint tiles;
  uint rate_tiles_x;  // VRCS: 8x8 rate tiles per row
  uint sheen_lobe;    // 0: the cloth workload and the uber kernel skip the sheen lobe (negative control)
  uint pad1, pad2;
};
GIB_SHARED_END
#endif
