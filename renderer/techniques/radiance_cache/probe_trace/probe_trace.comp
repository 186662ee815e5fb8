#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "renderer/techniques/radiance_cache/probe_trace/probe_trace_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kProbeTraceSpecAlpha
#include "bvh_alpha.glsl"

layout(local_size_x = kProbeTraceGroup) in;
layout(std430, set = 0, binding = kProbeTraceBindHits) writeonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kProbeTraceBindActive) writeonly buffer ActiveBuffer { uint rc_active[]; };
layout(std430, set = 0, binding = kProbeTraceBindCounters) coherent buffer CounterBuffer {
  RcCounters counters;
  RcRoundArgs rounds[];  // rounds[r - 1]: insertion round r
};
layout(std430, set = 0, binding = kProbeTraceBindPending) coherent buffer PendingBuffer { uvec2 rc_pending[]; };
// Last frame's copy of the counters (ping-pong), which next frame's trace counts into.
layout(std430, set = 0, binding = kProbeTraceBindNextCounters) writeonly buffer NextCounterBuffer { uint next_counters[]; };
layout(push_constant) uniform Push { RcParams rc; uvec4 extra; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kProbeTraceBindCells, coherent)
#define RC_INSERT_SPEC_GROUP_COUNTS kProbeTraceSpecGroupCounts
#include "renderer/techniques/radiance_cache/include/rc_insert.glsl"

// Traces ray `id` (probe id / rays, ray id % rays of the updated cascade) and stores its hit
// record; returns its cell key (0: a miss, or a ray inside geometry).
uint trace_ray(uint id) {
  uint rays = rc_rays_per_probe();
  uint probe = id / rays, ray = id - probe * rays;
  uint c = rc_updated_cascade();
  vec3 o = rc_probe_position(c, rc_probe_coord(probe));
  vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));
  GibHit hit;
  ProbeHit h;
  if (trace_closest(o, d, 0.0, kProbeMissDistance, hit)) {
    h.triangle_plus1 = hit.triangle + 1u;
    uvec2 b = uvec2(clamp(vec2(hit.u, hit.v), 0.0, 1.0) * 65535.0 + 0.5);
    h.barycentrics = b.x | (b.y << 16u);
    h.distance = hit.t;
    // The cell key, once, here (the insertion below, radiance_cache_update's rounds and
    // irradiance_volume_update read it): the triangle and its vertices were just fetched by the
    // intersection.
    float lod;
    h.key = rc_probe_ray_inside(h, d, c) ? 0u
                                         : rc_cell_key(rc_hit_position(o, d, h.distance), rc_facing_normal(hit.triangle, d), lod);
  } else {
    h.triangle_plus1 = 0u;
    h.key = 0u;
    h.barycentrics = 0u;
    h.distance = kProbeMissDistance;
  }
  probe_hits[id] = h;
  return h.key;
}

// true: insertion round 0 (the find) runs here, as each ray is traced; false (option
// insertion_find 1): radiance_cache_update runs it in a dispatch of its own.
layout(constant_id = kProbeTraceSpecFind) const bool kFind = true;

void main() {
  uint id = gl_GlobalInvocationID.x;
  // The next frame's counters start at zero: zeroed here by the first group instead of by a
  // transfer fill between two barriers before this dispatch (~11 us on an H100).
  if (gl_WorkGroupID.x == 0u)
    for (uint w = gl_LocalInvocationIndex; w < uint(next_counters.length()); w += kProbeTraceGroup) next_counters[w] = 0u;
  bool valid = rc_is_hit_record(id);
  if (!kFind) {
    if (valid) trace_ray(id);
    return;
  }
  rc_insert_begin();
  uint key = valid ? trace_ray(id) : 0u;
  // Each ray hit triggers its cache update (the seed's): insertion round 0, the find, in uniform
  // control flow (every thread of the group reaches it).
  rc_insert_find(id, key);
  rc_insert_flush();
}
