// probe_trace <-> C++: bindings, group size and push constants.
#ifndef GIB_PROBE_TRACE_SHARED_H
#define GIB_PROBE_TRACE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kProbeTraceGroup, 64)      // one thread per (probe, ray)
GIB_CONST(uint, kProbeTraceBindHits, 8)    // writeonly ProbeHit probe_hits[]
GIB_CONST(uint, kProbeTraceSpecAlpha, 0)
GIB_CONST(uint, kProbeTraceMaxRays, 256)   // rays_per_probe above this is a settings error
// Rays are traced to this distance (m); a miss stores it as its distance.
GIB_CONST(float, kProbeMissDistance, 10000.0)
struct ProbeTracePush {
  RcParams rc;
};
GIB_SHARED_END
#endif
