// radiance_cache_shade <-> C++: bindings, group size, specialization constants, push constants.
#ifndef GIB_RADIANCE_CACHE_SHADE_SHARED_H
#define GIB_RADIANCE_CACHE_SHADE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
// Group size: kRcShadeGroup (radiance_cache_shared.h), the unit of the indirect args.
GIB_CONST(uint, kRcShadeBindHits, 8)             // readonly ProbeHit probe_hits[]
GIB_CONST(uint, kRcShadeBindActive, 9)           // readonly uint rc_active[]
GIB_CONST(uint, kRcShadeBindCounters, 10)        // readonly RcCounters
GIB_CONST(uint, kRcShadeBindCells, 11)           // RcCell rc_cells[]
GIB_CONST(uint, kRcShadeBindProbeIrradiance, 12) // last frame's probe_irradiance (r32ui RGB9E5)
GIB_CONST(uint, kRcShadeBindProbeVisibility, 13) // last frame's probe_visibility (rg16f)
GIB_CONST(uint, kRcShadeBindLightGrid, 14)       // light_grid (a placeholder buffer without local lights)
GIB_CONST(uint, kRcShadeSpecSun, 0)
GIB_CONST(uint, kRcShadeSpecSky, 1)
GIB_CONST(uint, kRcShadeSpecLocal, 2)
GIB_CONST(uint, kRcShadeSpecAlpha, 3)
GIB_CONST(uint, kRcShadeSpecDither, 4)  // 1: the cell's RGB9E5 store rounds stochastically (option dither_stores)
struct RcShadePush {
  RcParams rc;
  LightGridParams lg;  // x: cascade-0 extent (m), y: cascades, z: light count
  uvec4 inject;        // debug NaN injection: x 1 on the injection frame, y, z the pixel whose surface cell gets it
};
GIB_SHARED_END
#endif
