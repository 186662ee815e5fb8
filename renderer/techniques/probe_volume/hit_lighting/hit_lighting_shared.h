// hit_lighting <-> C++: bindings, group size, push constants.
#ifndef GIB_HIT_LIGHTING_SHARED_H
#define GIB_HIT_LIGHTING_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvHitLightingGroup, 8)
GIB_CONST(uint, kPvHitLightingBindState, 8)
GIB_CONST(uint, kPvHitLightingBindIrradiance, 9)
GIB_CONST(uint, kPvHitLightingBindRadiance, 10)
GIB_CONST(uint, kPvHitLightingBindVisibility, 11)
GIB_CONST(uint, kPvHitLightingBindPosition, 12)
GIB_CONST(uint, kPvHitLightingBindNormal, 13)
GIB_CONST(uint, kPvHitLightingBindEmissive, 14)
GIB_CONST(uint, kPvHitLightingBindHits, 15)   // pixel_hits
GIB_CONST(uint, kPvHitLightingBindSh, 16)     // pixel_sh (rg32ui, ycocg_sh.glsl)
GIB_CONST(uint, kPvHitLightingSpecAlpha, 0)
GIB_CONST(uint, kPvHitLightingSpecSun, 1)
GIB_CONST(uint, kPvHitLightingSpecLocal, 2)
// Probe AO (AC Shadows "Indirect occlusion"): irradiance at a hit closer than one spacing is
// scaled by saturate(distance / spacing x kPvProbeAoScale + kPvProbeAoBias).
GIB_CONST(float, kPvProbeAoScale, 0.5)
GIB_CONST(float, kPvProbeAoBias, 0.5)
struct PvHitLightingPush {
  PvParams pv;
};
GIB_SHARED_END
#endif
