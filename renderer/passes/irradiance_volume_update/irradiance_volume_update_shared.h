// irradiance_volume_update <-> C++: bindings, group size, push constants.
#ifndef GIB_IRRADIANCE_VOLUME_UPDATE_SHARED_H
#define GIB_IRRADIANCE_VOLUME_UPDATE_SHARED_H
#include "frame_shared.h"
#include "radiance_cache_shared.h"
GIB_SHARED_BEGIN
// One 8x8 group per probe of the updated cascade: thread = interior texel of its tile.
GIB_CONST(uint, kIvGroup, 8)
GIB_CONST(uint, kIvMaxRays, 256)                // rays per probe held in group-shared memory
GIB_CONST(uint, kIvBindHits, 8)                 // readonly ProbeHit probe_hits[]
GIB_CONST(uint, kIvBindCells, 9)                // readonly RcCell rc_cells[]
GIB_CONST(uint, kIvBindPrevIrradiance, 10)      // last frame's probe_irradiance (r32ui RGB9E5)
GIB_CONST(uint, kIvBindPrevVisibility, 11)      // last frame's probe_visibility (rg16f)
GIB_CONST(uint, kIvBindIrradiance, 12)          // this frame's probe_irradiance
GIB_CONST(uint, kIvBindVisibility, 13)          // this frame's probe_visibility
GIB_CONST(uint, kIvSpecCacheFallback, 0)        // 1: hits without a shaded cell use last frame's volumes
// Exponent k of the max(0, n.d)^k weight of the distance moments.
GIB_CONST(float, kIvDistanceSharpness, 16.0)
struct IvPush {
  RcParams rc;
};
GIB_SHARED_END
#endif
