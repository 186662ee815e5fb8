#version 460
#extension GL_GOOGLE_include_directive : require
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
layout(push_constant) uniform Push { RcParams rc; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"

void main() {
  uint id = gl_GlobalInvocationID.x;
  uint rays = rc_rays_per_probe();
  if (id >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return;
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
    // The cell key, once, here (radiance_cache_update inserts it, irradiance_volume_update looks
    // it up): the triangle and its vertices were just fetched by the intersection.
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
}
