#ifndef GIB_VRCS_RATE_SHARED_H
#define GIB_VRCS_RATE_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kVrcsBindVbuffer, 8)
GIB_CONST(uint, kVrcsBindTangentFrame, 9)
GIB_CONST(uint, kVrcsBindPrevLuma, 10)   // last frame's vrcs_luma (r32f, tone-mapped)
GIB_CONST(uint, kVrcsBindRates, 11)      // vrcs_rates (layout: deferred_shared.h)
struct VrcsPush {
  float threshold;   // largest tone-mapped luma step between the two pixels of a coarse pair
  uint edges;        // 1: instance changes and normal creases keep full rate
  uint force;        // 0: choose; else this rate everywhere (1 2x1, 2 1x2, 3 2x2): controls
  uint history;      // 0: no last frame yet: full rate everywhere
  uint rate_tiles_x;
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
