// probe_relight: lights the selected probes' G-buffer texels (see probe_relight.h); five
// kernels chosen by the specialisation constant kKernel.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/probe_relight/probe_relight_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kPvRelightSpecAlpha
#include "bvh_alpha.glsl"
#include "surface.glsl"
#include "lights.glsl"
#include "sampling.glsl"
layout(constant_id = kPvRelightSpecLocal) const bool kHasLocal = true;
layout(constant_id = kPvRelightSpecSky) const bool kHasSky = true;
layout(constant_id = kPvRelightSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvRelightBindState, )
layout(std430, set = 0, binding = kPvRelightBindSelection) readonly buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
layout(std430, set = 0, binding = kPvRelightBindMaterial) readonly buffer MaterialBuffer { uvec2 gb_material[]; };
layout(std430, set = 0, binding = kPvRelightBindNormal) readonly buffer NormalBuffer { uint gb_normal[]; };
PV_GBUFFER_DEPTH(kPvRelightBindDepth, readonly)
layout(std430, set = 0, binding = kPvRelightBindTexels) buffer TexelBuffer {
  PvTexelLists lists;
  uint texel_list[];
};
layout(std430, set = 0, binding = kPvRelightBindRadiance) writeonly buffer RadianceOut { vec4 texel_radiance[]; };
layout(std430, set = 0, binding = kPvRelightBindLocal) writeonly buffer LocalOut { float texel_local[]; };
PV_PROBE_BUFFERS(kPvRelightBindIrradiance, kPvRelightBindProbeRadiance, kPvRelightBindVisibility)
#include "renderer/techniques/probe_volume/include/pv_sample.glsl"
#include "renderer/techniques/probe_volume/include/pv_shade.glsl"
layout(local_size_x = kPvRelightGroup) in;

uint list_capacity() { return pv.flags.y * kPvGbufferTexels; }

float texel_depth(uint probe, uint t) { return pv_texel_depth(probe, t, -1.0); }

void rescale() {
  uint probe = gl_GlobalInvocationID.x;
  if (probe == 0u) lists = PvTexelLists(uvec4(0u, 1u, 1u, 0u), uvec4(0u, 1u, 1u, 0u));
  if (probe >= pv_probe_count()) return;
  PvProbe p = pv_probes[probe];
  if ((uint(p.coord.w) & kPvProbeValid) == 0u || p.stamp.x == pv_frame() + 1u) return;
  float now = pv_sun_sky_estimate(p.meta.x);
  if (pv_flag(kPvFlagLightingScale)) {
    float before = p.meta.y * p.meta.x + p.meta.z;
    float after = now * p.meta.x + p.meta.z;
    // Stored lighting = true x scale: brighter light, smaller scale.
    if (before > 0.0 && after > 0.0) pv_probes[probe].offset.w = p.offset.w * (before / after);
  }
  pv_probes[probe].meta.y = now;
}

void classify() {
  uint e = gl_WorkGroupID.x;
  uint probe = pv_entries[e];
  bool quarter = (uint(pv_probes[probe].coord.w) & kPvProbeQuarter) != 0u;
  for (uint t = gl_LocalInvocationIndex; t < kPvGbufferTexels; t += kPvRelightGroup) {
    // A quarter-resolution probe's 2x2 blocks hold one texel four times: light it once.
    uint x = t % kPvGbufferSide, y = t / kPvGbufferSide;
    if (quarter && ((x | y) & 1u) != 0u) continue;
    bool hit = texel_depth(probe, t) >= 0.0;
    uint entry = (e << kPvTexelBits) | t;
    if (hit)
      texel_list[atomicAdd(lists.hit_args.w, 1u)] = entry;
    else
      texel_list[list_capacity() + atomicAdd(lists.miss_args.w, 1u)] = entry;
  }
}

void args() {
  if (gl_LocalInvocationIndex != 0u) return;
  lists.hit_args.x = (lists.hit_args.w + kPvRelightGroup - 1u) / kPvRelightGroup;
  lists.miss_args.x = (lists.miss_args.w + kPvRelightGroup - 1u) / kPvRelightGroup;
}

void light_hit() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= lists.hit_args.w) return;
  uint entry = texel_list[i];
  uint e = entry >> kPvTexelBits, t = entry & ((1u << kPvTexelBits) - 1u);
  uint probe = pv_entries[e];
  PvProbe p = pv_probes[probe];
  uint c = pv_cascade_of(probe);
  bool quarter = (uint(p.coord.w) & kPvProbeQuarter) != 0u;
  vec3 o = pv_cell_position(c, p.coord.xyz) + p.offset.xyz;
  vec3 d = pv_gbuffer_direction(t, quarter);
  float depth = texel_depth(probe, t);
  uint g = pv_gbuffer_index(probe, t);
  vec4 albedo_t = pv_unpack_albedo(gb_material[g]);
  uint nw = gb_normal[g];
  vec3 n = pv_unpack_normal(nw);
  vec3 x = o + d * (depth * (1.0 - kPvDepthPullback));  // in front of the surface (kPvDepthPullback)
  vec3 local = pv_local_lights(x, n, albedo_t.a);
  vec3 light = pv_sun(n, albedo_t.a, pv_unpack_shadow(nw)) + local;
  vec3 radiance = albedo_t.rgb * light / GIB_PI;
  if (pv_flag(kPvFlagMultiBounce)) radiance += albedo_t.rgb * pv_bounce(x, n, albedo_t.a, d, depth);
  if (pv_flag(kPvFlagNanGuards) && !gib_finite(radiance)) radiance = vec3(0.0);
  texel_radiance[e * kPvGbufferTexels + t] = vec4(radiance, 0.0);
  texel_local[e * kPvGbufferTexels + t] = gib_luminance(albedo_t.rgb * local / GIB_PI);
}

void light_miss() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= lists.miss_args.w) return;
  uint entry = texel_list[list_capacity() + i];
  uint e = entry >> kPvTexelBits, t = entry & ((1u << kPvTexelBits) - 1u);
  uint probe = pv_entries[e];
  PvProbe p = pv_probes[probe];
  uint c = pv_cascade_of(probe);
  bool quarter = (uint(p.coord.w) & kPvProbeQuarter) != 0u;
  vec3 d = pv_gbuffer_direction(t, quarter);
  vec3 end = pv_cell_position(c, p.coord.xyz) + p.offset.xyz + d * pv_trace_range(c);
  bool indoor = pv_point_indoor(end, vec3(0.0));
  // Inside the volume: the filtered radiance probes there (a coarser cascade's, typically);
  // outside: the sky, whole (its radiance is added where it is used, from the direction).
  // Single bounce (multi_bounce 0): the radiance probes' sky visibility only.
  vec4 r = pv_cascade_at(end) < kPvMaxCascades ? pv_sample_radiance(end, d, indoor) : vec4(0.0, 0.0, 0.0, 1.0);
  if (!pv_flag(kPvFlagMultiBounce)) r.rgb = vec3(0.0);
  texel_radiance[e * kPvGbufferTexels + t] = r;
  texel_local[e * kPvGbufferTexels + t] = 0.0;
}

void main() {
  if (kKernel == kPvRelightRescale) rescale();
  else if (kKernel == kPvRelightClassify) classify();
  else if (kKernel == kPvRelightArgs) args();
  else if (kKernel == kPvRelightHit) light_hit();
  else light_miss();
}
