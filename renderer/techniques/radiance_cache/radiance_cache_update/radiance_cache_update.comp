#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
layout(constant_id = kRcUpdateSpecKernel) const uint kKernel = kRcUpdateKernelRounds;

layout(local_size_x = kRcUpdateGroup) in;
layout(std430, set = 0, binding = kRcUpdateBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kRcUpdateBindActive) writeonly buffer ActiveBuffer { uint rc_active[]; };
layout(std430, set = 0, binding = kRcUpdateBindCounters) coherent buffer CounterBuffer {
  RcCounters counters;
  RcRoundArgs rounds[];  // rounds[r - 1]: insertion round r
};
layout(std430, set = 0, binding = kRcUpdateBindPending) coherent buffer PendingBuffer { uvec2 rc_pending[]; };
layout(push_constant) uniform Push { RcParams rc; uvec4 extra; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kRcUpdateBindCells, coherent)

#define RC_INSERT_SPEC_GROUP_COUNTS kRcUpdateSpecGroupCounts
#include "renderer/techniques/radiance_cache/include/rc_insert.glsl"

shared uint s_round_count;

// Round `round`'s pending entry idx (nothing past the list's length).
void round_step(uint round, uint idx) {
  uint id = kNoCell, key = 0u;
  if (idx < rounds[round - 1u].count) {
    uvec2 e = rc_pending[(round & 1u) * extra.z + idx];
    id = e.x;
    key = e.y;
  }
  rc_insert_step(round, id, key);
}

void main() {
  rc_insert_begin();
  if (kKernel == kRcUpdateKernelFind) {
    // Round 0 over every hit record (option insertion_find 1; by default probe_trace runs it as
    // it traces): the same step on the same committed keys.
    uint id = gl_GlobalInvocationID.x;
    rc_insert_find(id, rc_is_hit_record(id) ? probe_hits[id].key : 0u);
  } else if (kKernel == kRcUpdateKernelRound) {
    round_step(extra.y, gl_GlobalInvocationID.x);
  } else {
    // Every round in one workgroup (option insertion_rounds 0): the group walks round r's list
    // in strides of its size, then a buffer barrier and a group barrier close the round, as the
    // end of a dispatch would. Within a round the strides are one order the threads of a
    // dispatch could have run in, and the rounds' outcome does not depend on that order, so the
    // table and counters equal those of one dispatch per round. One dispatch instead of
    // max_probe indirect ones (each ~4.7 us of launch and barrier on an H100 even with 0 groups).
    for (uint round = 1u; round <= rc_max_probe(); ++round) {
      if (gl_LocalInvocationIndex == 0u) s_round_count = rounds[round - 1u].count;
      barrier();
      uint n = s_round_count;
      if (n == 0u) break;  // nothing pending: no later round has anything either (uniform: shared)
      for (uint base = 0u; base < n; base += kRcUpdateGroup) round_step(round, base + gl_LocalInvocationIndex);
      memoryBarrierBuffer();
      barrier();
    }
  }
  rc_insert_flush();
}
