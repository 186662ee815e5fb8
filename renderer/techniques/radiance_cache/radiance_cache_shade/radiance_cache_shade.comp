#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
layout(constant_id = kRcShadeSpecSun) const bool kHasSun = true;
layout(constant_id = kRcShadeSpecSky) const bool kHasSky = true;
layout(constant_id = kRcShadeSpecLocal) const bool kHasLocal = true;
layout(constant_id = kRcShadeSpecDither) const bool kDither = false;
#define GIB_ALPHA_SPEC kRcShadeSpecAlpha
#include "bvh_alpha.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"

layout(local_size_x = kRcShadeGroup) in;
layout(std430, set = 0, binding = kRcShadeBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kRcShadeBindActive) readonly buffer ActiveBuffer { uint rc_active[]; };
layout(std430, set = 0, binding = kRcShadeBindCounters) readonly buffer CounterBuffer { RcCounters counters; };
layout(push_constant) uniform Push {
  RcParams rc;
  LightGridParams lg;
  uvec4 inject;
};
#define RC_PROBE_RAYS
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kRcShadeBindProbeIrradiance, kRcShadeBindProbeVisibility)
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kRcShadeBindCells, )
#define LG_PARAMS lg
#include "renderer/techniques/radiance_cache/include/light_grid.glsl"
RC_LIGHT_GRID_BUFFER(kRcShadeBindLightGrid)

const float kFar = 3.4e38;

// Direct light leaving x towards the side n (sun: one sample of its cone; local lights from the
// light grid), each behind one shadow ray: what a cell adds to the light arriving from elsewhere.
vec3 direct_light(vec3 x, vec3 n, vec3 albedo, float translucency, inout GibRng rng) {
  vec3 result = vec3(0.0);
  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
    vec3 wi = gib_uniform_cone(gib_frame.sun_dir.xyz, gib_frame.sun_dir.w, gib_next2(rng));
    float w = gib_thin_facing(translucency, n, wi);
    if (w > 0.0 && !trace_any(gib_offset_ray(x, dot(n, wi) > 0.0 ? n : -n), wi, 0.0, kFar))
      result += albedo / GIB_PI * w * gib_frame.sun_irradiance.rgb;
  }
  if (kHasLocal) {
    uint base = lg_cell_base(x);
    if (base != kLgInvalid) {
      uint count = min(LG_CELL_COUNT(base), kLightGridMaxLights);
      for (uint i = 0u; i < count; ++i) {
        vec3 wi;
        float dist;
        vec3 e = gib_local_light(gib_lights[LG_CELL_LIGHT(base, i)], x, wi, dist);
        float w = gib_thin_facing(translucency, n, wi);
        if (w <= 0.0 || all(equal(e, vec3(0.0)))) continue;
        if (!trace_any(gib_offset_ray(x, dot(n, wi) > 0.0 ? n : -n), wi, 0.0, dist * 0.999))
          result += albedo / GIB_PI * w * e;
      }
    }
  }
  return result;
}

// Radiance leaving the surface at a hit of a bounce ray travelling along wi.
vec3 bounce_radiance(GibHit hit, vec3 wi, uint now, inout GibRng rng) {
  // The back of a solid's face: the ray slipped into a wall (from a cell on an edge); nothing
  // inside is lit, and the cells and probes there hold the outside's light.
  if ((rc.flags.x & kRcFlagInsideTest) != 0u && rc_inside_solid(hit.triangle, wi)) return vec3(0.0);
  GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, rc.flags.y != 0u);
  // Single bounce (multi_bounce 0): only what the hit emits; cached cells and the volumes both
  // hold light that has already bounced.
  if (rc.flags.z == 0u) return gib_material_emissive(gib_materials[s.material], s.uv);
  vec3 q = s.position;
  float lod;
  uint i = rc_find_cell(rc_cell_key(q, rc_facing_normal(hit.triangle, wi), lod));
  if (i != 0xffffffffu) {
    uint shaded = rc_cells[i].shaded_frame;
    if (shaded != 0u && shaded != now) return gib_unpack_rgb9e5(rc_cells[i].radiance);
  }
  // No cell to read (none inserted there, or it is being shaded this frame): the hit's own
  // estimate. The volumes hold light that reached the probes from surfaces and the sky, not the
  // sun's or local lights' direct light at q, so that is traced here as a cell's shade does;
  // without it a bounce onto a sunlit patch whose cell is shaded in the same frame loses the
  // patch's sunlight (thin-wall-leak-005 at high: 0.782 of the reference instead of 1.035).
  GpuMaterial m = gib_materials[s.material];
  vec3 n = dot(s.normal, wi) > 0.0 ? -s.normal : s.normal;
  vec3 albedo = gib_material_albedo(m, s.uv);
  return gib_material_emissive(m, s.uv) + direct_light(q, n, albedo, m.translucency, rng) +
         albedo * rc_sample_irradiance(q, n, -wi);
}

// Debug NaN injection target: the cell of the camera's first hit through pixel inject.yz, keyed
// on the side facing the camera (what a gather ray arriving from the camera's side looks up);
// 0xffffffff when that ray misses or no probe ray ever inserted the cell.
uint injection_cell() {
  vec3 o, d;
  gib_camera_ray(vec2(inject.yz) + 0.5, o, d);
  GibHit hit;
  if (!trace_closest(o, d, 0.0, kFar, hit)) return 0xffffffffu;
  GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, rc.flags.y != 0u);
  float lod;
  return rc_find_cell(rc_cell_key(s.position, rc_facing_normal(hit.triangle, d), lod));
}

void store(uint cell, vec3 result, uint now) {
  if (rc.flags.y != 0u && !gib_finite(result)) {
    // Guard: a non-finite shade is not kept. The cell reads as never shaded (every reader
    // misses it and falls back to the volumes) and the next probe hit on it queues it again.
    rc_cells[cell].radiance = 0u;
    rc_cells[cell].shaded_frame = 0u;
    return;
  }
  // RGB9E5 has no NaN: a NaN packs to 0. dither_stores: stochastic rounding (a dither from the
  // cell and the frame), so a cell re-shaded to the same value does not round the same way each
  // time: rounded to nearest, the closed box's 100x loop gain turned the rounding into a bias.
  uint dither = gib_pcg(cell ^ gib_pcg(now ^ 0x3c6ef372u));
  rc_cells[cell].radiance = kDither ? gib_pack_rgb9e5_dither(result, dither) : gib_pack_rgb9e5(result);
  rc_cells[cell].shaded_frame = now;
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  uint now = rc.misc.x + 1u;
  uint target = inject.x != 0u ? injection_cell() : 0xffffffffu;
  // A target cell not queued this frame is written by thread 0 as if shaded now (its queued
  // twin, if any, injects below; both write the same).
  if (index == 0u && target != 0xffffffffu && rc_cells[target].shaded_frame != now) store(target, vec3(gib_nan()), now);
  if (index >= counters.active_cells) return;
  uint cell = rc_active[index];
  // ~(lowest hit id) of the cell's hits (radiance_cache_update); reset to 0 for the next frame's
  // update, which offers its hits by atomicMax.
  uint hit_id = ~rc_cells[cell].hit_index;
  rc_cells[cell].hit_index = 0u;
  ProbeHit h = probe_hits[hit_id];
  uint rays = rc_rays_per_probe();
  uint probe = hit_id / rays, ray = hit_id - probe * rays;
  vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));

  uint tri = h.triangle_plus1 - 1u;
  vec2 bary = vec2(h.barycentrics & 0xffffu, h.barycentrics >> 16u) * (1.0 / 65535.0);
  GibSurface s = gib_surface(tri, bary.x, bary.y, rc.flags.y != 0u);
  GpuMaterial m = gib_materials[s.material];
  vec3 albedo = gib_material_albedo(m, s.uv);
  float translucency = m.translucency;
  // The side the probe ray saw.
  vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  vec3 x = s.position;
  GibRng rng = gib_rng(gib_seed(), rc.misc.x, uvec2(cell, hit_id), 21u);
  vec3 result = gib_material_emissive(m, s.uv);

  result += direct_light(x, n, albedo, translucency, rng);
  {
    // Sky and bounce: one cosine ray on the front, or (translucency) on the back.
    vec3 side = translucency > 0.0 && gib_next(rng) < translucency ? -n : n;
    vec3 wi = gib_cosine_hemisphere(side, gib_next2(rng));
    GibHit hit;
    vec3 l;
    if (!trace_closest(gib_offset_ray(x, side), wi, 0.0, kFar, hit))
      l = kHasSky ? gib_sky_radiance(wi) : vec3(0.0);
    else
      l = bounce_radiance(hit, wi, now, rng);
    result += albedo * l;
  }
  if (cell == target) result = vec3(gib_nan());
  store(cell, result, now);
}
