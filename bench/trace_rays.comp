#version 460
#extension GL_GOOGLE_include_directive : require
#include "bench/trace_rays_shared.h"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kTraceRaysBindScene)
bool gib_alpha_accept(uint triangle, float u, float v, inout uint calls, uint ray_key) { return true; }
#include "bvh.glsl"

layout(local_size_x = kTraceRaysGroup) in;
layout(std430, set = 0, binding = kTraceRaysBindRays) readonly buffer Rays { TraceRay rays[]; };
layout(std430, set = 0, binding = kTraceRaysBindHits) writeonly buffer Hits { float hits[]; };
layout(push_constant) uniform Push { TraceRaysPush push; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.ray_count) return;
  TraceRay r = rays[i];
  float t = -1.0;
  if (push.any_hit != 0u) {
    t = trace_any(r.origin_tmin.xyz, r.dir_tmax.xyz, r.origin_tmin.w, r.dir_tmax.w) ? 1.0 : 0.0;
  } else {
    GibHit h;
    if (trace_closest(r.origin_tmin.xyz, r.dir_tmax.xyz, r.origin_tmin.w, r.dir_tmax.w, h)) t = h.t;
  }
  hits[i] = t;
}
