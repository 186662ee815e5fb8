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
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"
layout(set = 0, binding = kPvWorldTraceBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvWorldTraceBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvWorldTraceBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kPvWorldTraceBindHits, rgba32ui) uniform uimage2D out_hits;
layout(local_size_x = kPvWorldTraceGroup, local_size_y = kPvWorldTraceGroup) in;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(out_hits)))) return;
  uvec4 prior = imageLoad(out_hits, q);
  if ((prior.w & kPvPixelWorld) == 0u) return;  // settled on screen, or no surface
  ivec2 p = pv_source_pixel(q);
  vec3 pos = imageLoad(gb_position, p).xyz;
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (!(gib_finite(n) && dot(n, n) > 0.25)) n = normalize(gib_frame.camera_pos.xyz - pos);  // NaN guard
  n = normalize(n);
  float translucency = imageLoad(gb_emissive, p).w;
  PvPixelRay r = pv_pixel_ray(q, pos, n, translucency);
  uint c = pv_cascade_at(pos);
  float range = pv.volume.w * pv_trace_range(min(c, pv_cascades() - 1u));
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
  uvec2 o = uvec2(clamp(gib_oct_encode(hn), 0.0, 1.0) * 65535.0 + 0.5);
  imageStore(out_hits, q, uvec4(mat.x, o.x | (o.y << 16u), floatBitsToUint(hit.t), flags | kPvPixelHit));
}
