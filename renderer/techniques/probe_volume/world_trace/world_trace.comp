// world_trace: one cosine ray per ray pixel through the BVH (see world_trace.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/world_trace/world_trace_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kPvWorldTraceSpecAlpha
#include "bvh_alpha.glsl"
#include "surface.glsl"
#include "sampling.glsl"
#include "ycocg_sh.glsl"
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvWorldTraceBindState, readonly)
#include "renderer/techniques/probe_volume/include/pv_volume.glsl"
layout(set = 0, binding = kPvWorldTraceBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvWorldTraceBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvWorldTraceBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
#define PV_PIXEL_GBUFFER
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"
layout(set = 0, binding = kPvWorldTraceBindHits, rgba32ui) uniform uimage2D out_hits;
layout(local_size_x = kPvWorldTraceGroup, local_size_y = kPvWorldTraceGroup) in;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(out_hits)))) return;
  uvec4 prior = imageLoad(out_hits, q);
  if ((prior.w & kPvPixelWorld) == 0u) return;  // settled on screen, or no surface
  ivec2 p = pv_source_pixel(q);
  vec3 pos = imageLoad(gb_position, p).xyz;
  PvPixelRay r = pv_pixel_ray_from(q, p, pos);
  float range = pv_pixel_range(pos);
  float start = max(uintBitsToFloat(prior.z), pv_min_start());
  uint flags = prior.w;
  GibHit hit;
  if (!trace_closest(r.origin, r.dir, start, range, hit)) {
    imageStore(out_hits, q, uvec4(0u, 0u, floatBitsToUint(range), flags));
    return;
  }
  GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, pv_flag(kPvFlagNanGuards));
  GpuMaterial m = gib_materials[s.material];
  vec3 hn = dot(s.normal, r.dir) > 0.0 ? -s.normal : s.normal;  // the side the ray sees
  uvec2 mat = pv_pack_material(gib_material_albedo(m, s.uv), m.translucency, vec3(0.0));
  imageStore(out_hits, q, uvec4(mat.x, pv_pack_normal16(hn), floatBitsToUint(hit.t), flags | kPvPixelHit));
}
