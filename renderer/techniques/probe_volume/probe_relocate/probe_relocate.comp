// probe_relocate: moves traced probes out of or away from geometry (see probe_relocate.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/probe_relocate/probe_relocate_shared.h"
#include "frame.glsl"
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvRelocateBindState, )
layout(std430, set = 0, binding = kPvRelocateBindSelection) readonly buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
PV_GBUFFER_DEPTH(kPvRelocateBindDepth, readonly)
layout(local_size_x = kPvRelocateGroup) in;

shared uint s_key[kPvRelocateGroup];

void main() {
  uint probe = pv_entries[gl_WorkGroupID.x];
  uint tid = gl_LocalInvocationIndex;
  PvProbe p = pv_probes[probe];
  uint c = pv_cascade_of(probe);
  float s = pv_spacing(c), range = pv_trace_range(c);
  // The deepest texel (a miss counts as the full range); ties: the lowest texel.
  uint best = 0u;
  for (uint t = tid; t < kPvGbufferTexels; t += kPvRelocateGroup) {
    float depth = min(pv_texel_depth(probe, t, range), range);
    uint key = (uint(depth / range * 4194303.0) << 9u) | (511u - t);
    best = max(best, key);
  }
  s_key[tid] = best;
  barrier();
  if (tid != 0u) return;
  for (uint i = 1u; i < kPvRelocateGroup; ++i) best = max(best, s_key[i]);
  uint deepest = 511u - (best & 511u);
  float max_depth = float(best >> 9u) / 4194303.0 * range;
  uint f = uint(p.coord.w);
  bool inside = p.geometry.x > kPvInsideBackfaces;
  bool near = p.geometry.y < kPvNearSpacings * s;
  if (!pv_flag(kPvFlagRelocation)) {
    pv_probes[probe].coord.w = int(f & ~kPvProbeDisabled);
    return;
  }
  if (!inside && !near) {
    pv_probes[probe].coord.w = int(f & ~kPvProbeDisabled);
    return;
  }
  // Towards the deepest direction, half of its depth, within the cell's offset box.
  vec3 dir = pv_gbuffer_direction(deepest, (f & kPvProbeQuarter) != 0u);
  float limit = kPvMaxOffsetSpacings * s;
  vec3 moved = clamp(p.offset.xyz + dir * min(0.5 * max_depth, limit), vec3(-limit), vec3(limit));
  bool moves = distance(moved, p.offset.xyz) > 0.05 * s;
  if (moves) {
    pv_probes[probe].pending = vec4(moved, 0.0);
    f |= kPvProbeRetrace;  // probe_select re-traces it there first among the G-buffer refreshes
  }
  // Inside: disabled (samplers skip it) until a later trace finds it outside, also while a move
  // is pending (its lighting is still the one seen from inside; a probe behind a closed box's
  // wall kept lighting the walls' samples with the void's darkness while it moved).
  if (inside) f |= kPvProbeDisabled;
  else f &= ~kPvProbeDisabled;
  pv_probes[probe].coord.w = int(f);
  pv_probes[probe].geometry.w = float(deepest);
}
