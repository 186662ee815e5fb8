// irradiance_volume_update, step 1: the radiance arriving along every ray of every probe of
// the updated cascade (cache radiance at the hit, volumes as fallback, sky on a miss), one
// invocation per ray, into probe_ray_radiance (rgb, clamped hit distance). Step 2
// (irradiance_volume_update.comp) convolves them per atlas texel. Two barrier-free kernels
// instead of one workgroup per probe with group-shared rays: on lavapipe the barriers cost
// ~70 us per workgroup (300 ms per frame for 4096 probes); GPUs do not mind either way.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "material.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"
#include "hash.glsl"
#define GIB_ALPHA_SPEC kIvSpecAlpha
#include "bvh_alpha.glsl"
layout(constant_id = kIvSpecCacheFallback) const bool kCacheFallback = true;

layout(local_size_x = kIvRaysGroup) in;
layout(std430, set = 0, binding = kIvBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kIvBindRays) writeonly buffer RayBuffer { vec4 probe_ray_radiance[]; };
layout(push_constant) uniform Push { RcParams rc; };
#define RC_PROBE_RAYS
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kIvBindPrevIrradiance, kIvBindPrevVisibility)
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kIvBindCells, readonly)
#define IV_SHADE_RAYS
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_common.glsl"

void main() {
  uint rays = rc_rays_per_probe();
  uint i = gl_GlobalInvocationID.x;
  if (i >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return;
  uint probe = i / rays, r = i % rays;
  uint c = rc_updated_cascade();
  vec3 o = rc_probe_position(c, rc_probe_coord(probe));
  vec3 d = rc_ray_direction(r, rays, rc_frame_rotation(rc.misc.x));
  ProbeHit h = probe_hits[i];
  vec3 l;
  // A ray that brings no light is marked by a negative distance (weight 0 in every texel): -1
  // dropped by the guard, kIvInsideMark inside geometry.
  uint state = iv_ray_radiance(h, o, d, c, l);
  probe_ray_radiance[i] = state == kIvRayLit ? vec4(l, min(h.distance, rc_moment_max_distance(c)))
                                             : vec4(0.0, 0.0, 0.0, state == kIvRayInside ? kIvInsideMark : -1.0);
}
