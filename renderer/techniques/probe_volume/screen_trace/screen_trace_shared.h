// screen_trace <-> C++: bindings, group size, push constants.
#ifndef GIB_SCREEN_TRACE_SHARED_H
#define GIB_SCREEN_TRACE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvScreenTraceGroup, 8)
GIB_CONST(uint, kPvScreenTraceBindState, 8)
GIB_CONST(uint, kPvScreenTraceBindPosition, 9)
GIB_CONST(uint, kPvScreenTraceBindNormal, 10)
GIB_CONST(uint, kPvScreenTraceBindEmissive, 11)
GIB_CONST(uint, kPvScreenTraceBindAlbedo, 12)
GIB_CONST(uint, kPvScreenTraceBindHits, 13)   // pixel_hits (rgba32ui)
GIB_CONST(uint, kPvScreenTraceBindStats, 14)  // pixel_trace_stats
struct PvScreenTracePush {
  PvParams pv;
  vec4 screen;  // x: steps (0: off, every ray to world_trace), y: thickness (m), z: 1 = world rays resume
                // from the last visible point (the seed's backtracking), 0 = from the start; w: unused
};
GIB_SHARED_END
#endif
