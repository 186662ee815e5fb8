// Shared by bench/bench_trace.cpp and bench/trace_rays.comp: a ray-throughput kernel that
// traces rays from a buffer (closest hit or any hit) and writes the hit distance.
#ifndef GIB_TRACE_RAYS_SHARED_H
#define GIB_TRACE_RAYS_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kTraceRaysGroup, 64)
GIB_CONST(uint, kTraceRaysBindScene, 1)  // scene buffers at 1..7 (frame slot 0 unused)
GIB_CONST(uint, kTraceRaysBindRays, 8)
GIB_CONST(uint, kTraceRaysBindHits, 9)
struct TraceRay {  // 32 bytes
  vec4 origin_tmin;
  vec4 dir_tmax;
};
struct TraceRaysPush {
  uint ray_count;
  uint any_hit;  // 1: shadow-ray query (trace_any), 0: closest hit
};
GIB_SHARED_END
#endif
