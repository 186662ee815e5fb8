// probe_gbuffer: traces the texel centres of each traced probe's 20x20 octahedral tile (see
// probe_gbuffer.h). One workgroup per probe; a thread traces a pair of texels (full
// resolution) or one 2x2 block (quarter resolution, written to its four texels).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/probe_gbuffer/probe_gbuffer_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kPvGbufferSpecAlpha
#include "bvh_alpha.glsl"
#include "surface.glsl"
layout(constant_id = kPvGbufferSpecSun) const bool kHasSun = true;
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvGbufferBindState, )
layout(std430, set = 0, binding = kPvGbufferBindSelection) readonly buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
layout(std430, set = 0, binding = kPvGbufferBindMaterial) buffer MaterialBuffer { uvec2 gb_material[]; };
layout(std430, set = 0, binding = kPvGbufferBindNormal) buffer NormalBuffer { uint gb_normal[]; };
PV_GBUFFER_DEPTH(kPvGbufferBindDepth, )
layout(local_size_x = kPvGbufferGroup) in;

shared uint s_backfaces, s_backfaces_all, s_hits, s_min_depth, s_max_key;

struct Texel {
  uvec2 material;
  uint normal;
  uint depth;  // half-float bits
};

Texel trace_texel(vec3 o, vec3 d, float range, float reach) {
  Texel r;
  GibHit hit;
  if (!trace_closest(o, d, 0.0, range, hit)) {
    r.material = uvec2(0u);
    r.normal = 0u;
    r.depth = kPvMissDepthBits;
    atomicMax(s_max_key, (65534u << 16u));
    return r;
  }
  GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, pv_flag(kPvFlagNanGuards));
  GpuMaterial m = gib_materials[s.material];
  bool back = dot(s.normal, d) > 0.0;
  // A thin translucent sheet has no inside: its back is not a sign of being in geometry.
  // Within reach of the probe's cell only: a room modelled as a closed box seen from inside shows
  // back faces everywhere (our surfaces are two-sided), a probe inside a wall sees them close.
  if (back && m.translucency == 0.0) {
    if (hit.t < reach) atomicAdd(s_backfaces, 1u);
    atomicAdd(s_backfaces_all, 1u);
  }
  atomicAdd(s_hits, 1u);
  vec3 n = back ? -s.normal : s.normal;  // the side the probe sees
  float sun = kHasSun ? pv_sun_visibility(s.position, n, m.translucency) : 0.0;
  r.material = pv_pack_material(gib_material_albedo(m, s.uv), m.translucency, gib_material_emissive(m, s.uv));
  r.normal = pv_pack_normal_shadow(n, sun);
  r.depth = gib_float_to_half(hit.t);
  atomicMin(s_min_depth, floatBitsToUint(hit.t));
  atomicMax(s_max_key, (uint(clamp(hit.t / range, 0.0, 1.0) * 65534.0) << 16u));
  return r;
}

void store(uint probe, uint t, Texel a, Texel b) {
  uint g = pv_gbuffer_index(probe, t);
  gb_material[g] = a.material;
  gb_material[g + 1u] = b.material;
  gb_normal[g] = a.normal;
  gb_normal[g + 1u] = b.normal;
  gb_depth[g >> 1u] = a.depth | (b.depth << 16u);
}

void main() {
  uint probe = pv_entries[gl_WorkGroupID.x];
  uint tid = gl_LocalInvocationIndex;
  bool quarter = pv_probes[probe].stamp.y == kPvClassNew && pv_flag(kPvFlagQuarterNew);
  uint c = pv_cascade_of(probe);
  PvProbe p = pv_probes[probe];
  // A probe probe_relocate moved is traced at its new offset, which it keeps from now on.
  if ((uint(p.coord.w) & kPvProbeRetrace) != 0u) p.offset.xyz = p.pending.xyz;
  vec3 o = pv_cell_position(c, p.coord.xyz) + p.offset.xyz;
  float range = pv_trace_range(c);
  float reach = kPvBackfaceReach * pv_spacing(c);
  if (tid == 0u) {
    s_backfaces = 0u;
    s_backfaces_all = 0u;
    s_hits = 0u;
    s_min_depth = floatBitsToUint(range);
    s_max_key = 0u;
  }
  barrier();
  if (quarter) {
    for (uint b = tid; b < kPvGbufferTexels / 4u; b += kPvGbufferGroup) {
      uint t = (b / (kPvGbufferSide / 2u)) * 2u * kPvGbufferSide + (b % (kPvGbufferSide / 2u)) * 2u;
      Texel r = trace_texel(o, pv_gbuffer_direction(t, true), range, reach);
      store(probe, t, r, r);
      store(probe, t + kPvGbufferSide, r, r);
    }
  } else {
    for (uint pair = tid; pair < kPvGbufferTexels / 2u; pair += kPvGbufferGroup) {
      uint t = pair * 2u;
      Texel a = trace_texel(o, pv_gbuffer_direction(t, false), range, reach);
      Texel b = trace_texel(o, pv_gbuffer_direction(t + 1u, false), range, reach);
      store(probe, t, a, b);
    }
  }
  barrier();
  if (tid == 0u) {
    // The deepest direction: the texel whose (quantised) depth is largest; ties keep the
    // first found, so it is recomputed from the stored depths in probe_relocate.
    // Inside geometry (probe_relocate): the share of back faces among the hits, those within
    // reach, or all of them when some rays leave into open space: a probe behind a shell (the
    // outside of a closed box, under a terrain) sees only the shell's backs and the void, at any
    // distance, while one inside a room modelled as one box (back faces everywhere) sees no void.
    float hits = float(max(s_hits, 1u));
    bool open = s_hits < (quarter ? kPvGbufferTexels / 4u : kPvGbufferTexels);
    float inside = max(float(s_backfaces) / hits, open ? float(s_backfaces_all) / hits : 0.0);
    pv_probes[probe].geometry = vec4(inside, uintBitsToFloat(s_min_depth), float(s_max_key >> 16u) / 65534.0 * range, 0.0);
    uint f = (uint(p.coord.w) | kPvProbeTraced) & ~(kPvProbeRetrace | kPvProbeQuarter);
    pv_probes[probe].coord.w = int(f | (quarter ? kPvProbeQuarter : 0u));
    pv_probes[probe].offset.xyz = p.offset.xyz;
    pv_probes[probe].stamp.z = pv_frame() + 1u;
  }
}
