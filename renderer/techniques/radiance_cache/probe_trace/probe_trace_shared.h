// probe_trace <-> C++: bindings, group size and push constants.
#ifndef GIB_PROBE_TRACE_SHARED_H
#define GIB_PROBE_TRACE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kProbeTraceGroup, 64)      // one thread per (probe, ray)
GIB_CONST(uint, kProbeTraceBindHits, 8)    // writeonly ProbeHit probe_hits[]
// The insertion's round 0 (include/rc_insert.glsl): the buffers of radiance_cache_update.
GIB_CONST(uint, kProbeTraceBindCells, 9)    // coherent RcCell rc_cells[2^cache_log2_cells]
GIB_CONST(uint, kProbeTraceBindActive, 10)  // uint rc_active[capacity]: queued cell indices
GIB_CONST(uint, kProbeTraceBindCounters, 11)  // RcCounters (indirect args first), then RcRoundArgs[max_probe]
GIB_CONST(uint, kProbeTraceBindPending, 12)   // uvec2 rc_pending[2 * hits]: (hit id, key), two lists
GIB_CONST(uint, kProbeTraceBindNextCounters, 13)  // last frame's rc_counters copy, zeroed for the next frame
GIB_CONST(uint, kProbeTraceSpecAlpha, 0)
GIB_CONST(uint, kProbeTraceSpecGroupCounts, 1)  // bool: insertion counters summed per workgroup (GPUs)
GIB_CONST(uint, kProbeTraceSpecFind, 2)         // bool: insertion round 0 runs in the trace (option insertion_find 0)
GIB_CONST(uint, kProbeTraceMaxRays, 256)   // rays_per_probe above this is a settings error
// Rays are traced to this distance (m); a miss stores it as its distance.
GIB_CONST(float, kProbeMissDistance, 10000.0)
struct ProbeTracePush {
  RcParams rc;
  uvec4 extra;  // x: active-list capacity (entries), y: 0, z: pending-list capacity (hit records)
};
GIB_SHARED_END
#endif
