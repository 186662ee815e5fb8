// world_trace <-> C++: bindings, group size, push constants.
#ifndef GIB_WORLD_TRACE_SHARED_H
#define GIB_WORLD_TRACE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvWorldTraceGroup, 8)      // 8x8 ray pixels
GIB_CONST(uint, kPvWorldTraceBindState, 8)  // probe_state (cascade origins)
GIB_CONST(uint, kPvWorldTraceBindPosition, 9)
GIB_CONST(uint, kPvWorldTraceBindNormal, 10)
GIB_CONST(uint, kPvWorldTraceBindEmissive, 11)  // translucency in .w
GIB_CONST(uint, kPvWorldTraceBindHits, 12)      // pixel_hits (rgba32ui)
GIB_CONST(uint, kPvWorldTraceSpecAlpha, 0)
struct PvWorldTracePush {
  PvParams pv;
};
GIB_SHARED_END
#endif
