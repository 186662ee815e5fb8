// hit_lighting: light each per-pixel ray's hit or miss and encode it (see hit_lighting.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/hit_lighting/hit_lighting_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kPvHitLightingSpecAlpha
#include "bvh_alpha.glsl"
#include "surface.glsl"
#include "lights.glsl"
#include "sampling.glsl"
#include "ycocg_sh.glsl"
layout(constant_id = kPvHitLightingSpecSun) const bool kHasSun = true;
layout(constant_id = kPvHitLightingSpecLocal) const bool kHasLocal = true;
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvHitLightingBindState, readonly)
PV_PROBE_BUFFERS(kPvHitLightingBindIrradiance, kPvHitLightingBindRadiance, kPvHitLightingBindVisibility)
#include "renderer/techniques/probe_volume/include/pv_sample.glsl"
#include "renderer/techniques/probe_volume/include/pv_shade.glsl"
layout(set = 0, binding = kPvHitLightingBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvHitLightingBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvHitLightingBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
#define PV_PIXEL_GBUFFER
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"
layout(set = 0, binding = kPvHitLightingBindHits, rgba32ui) uniform readonly uimage2D in_hits;
layout(set = 0, binding = kPvHitLightingBindSh, rg32ui) uniform writeonly uimage2D out_sh;
layout(local_size_x = kPvHitLightingGroup, local_size_y = kPvHitLightingGroup) in;

// Bounce radiance arriving along the ray (emission and sky excluded: direct_lighting's).
vec3 ray_radiance(PvPixelRay r, uvec4 h) {
  float t = uintBitsToFloat(h.z);
  if ((h.w & kPvPixelHit) == 0u) {
    // Miss: the filtered radiance probes at the ray's end (reflected light only), else nothing.
    vec3 end = r.origin + r.dir * t;
    return pv_cascade_at(end) < kPvMaxCascades ? pv_sample_radiance(end, r.dir, pv_point_indoor(end, vec3(0.0))).rgb : vec3(0.0);
  }
  vec4 albedo_t = pv_unpack_albedo(uvec2(h.x, 0u));
  vec3 n = pv_unpack_normal16(h.y);
  vec3 x = r.origin + r.dir * t;
  float sun = kHasSun ? pv_sun_visibility(x, n, albedo_t.a) : 0.0;
  vec3 l = albedo_t.rgb * (pv_sun(n, albedo_t.a, sun) + pv_local_lights(x, n, albedo_t.a)) / GIB_PI;
  vec3 e = pv_bounce(x, n, albedo_t.a, r.dir, t);
  if (pv_flag(kPvFlagProbeAo)) {
    float s = pv_spacing(min(pv_cascade_at(x), pv_cascades() - 1u));
    e *= clamp(t / s * kPvProbeAoScale + kPvProbeAoBias, 0.0, 1.0);
  }
  return l + albedo_t.rgb * e;
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(out_sh)))) return;
  uvec4 h = imageLoad(in_hits, q);
  if ((h.w & kPvPixelValid) == 0u) {
    imageStore(out_sh, q, uvec4(gib_pack_ycocg_sh(0.0, vec3(0.0), vec2(0.0)), 0u, 0u));
    return;
  }
  ivec2 p = pv_source_pixel(q);
  vec3 position = imageLoad(gb_position, p).xyz;
  PvPixelRay r = pv_pixel_ray_from(q, p, position);
  vec3 e = GIB_PI * ray_radiance(r, h) * r.weight;
  if (pv_flag(kPvFlagLookupView)) {
    // Diagnostic: E at the pixel's own surface from the probes, seen from the camera, with a
    // flat SH (the per-pixel light is left out).
    vec3 to_camera = gib_frame.camera_pos.xyz - position;
    float dist = length(to_camera);
    vec3 n = normalize(imageLoad(gb_normal, p).xyz);
    e = GIB_PI * pv_bounce(position, n, imageLoad(gb_emissive, p).w, -to_camera / dist, dist);
    r.encode_dir = vec3(0.0);
  }
  if (pv_flag(kPvFlagNanGuards) && !gib_finite(e)) e = vec3(0.0);
  vec3 ycocg = gib_rgb_to_ycocg(e);
  imageStore(out_sh, q, uvec4(gib_pack_ycocg_sh(ycocg.x, ycocg.x * r.encode_dir, ycocg.yz), 0u, 0u));
}
