// probe_select: moves each cascade with the camera and picks this frame's probes (see
// probe_select.h). One workgroup; every list is compacted in probe order with a subgroup
// ballot and a scan over the subgroups, so the selection is the same on every run.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "renderer/techniques/probe_volume/probe_select/probe_select_shared.h"
#include "frame.glsl"
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvSelectBindState, )
layout(std430, set = 0, binding = kPvSelectBindSelection) buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
layout(local_size_x = kPvSelectGroup) in;

shared ivec3 s_origin[kPvMaxCascades];
shared uint s_subgroup[kPvSelectGroup];
shared uint s_count;  // entries written so far
shared uint s_scanned;  // round robin: slots passed over by the class's window in this cascade

// Appends `value` when `pred` (called by every thread of the group): entries keep thread order.
// Returns where this thread's value went, or ~0 when it was not stored (no pred, or past `limit`).
uint append(bool pred, uint value, uint limit) {
  uvec4 ballot = subgroupBallot(pred);
  if (subgroupElect()) s_subgroup[gl_SubgroupID] = subgroupBallotBitCount(ballot);
  barrier();
  uint before = s_count, total = 0u;
  for (uint i = 0u; i < gl_NumSubgroups; ++i) {
    if (i < gl_SubgroupID) before += s_subgroup[i];
    total += s_subgroup[i];
  }
  uint at = before + subgroupBallotExclusiveBitCount(ballot);
  bool stored = pred && at < limit;
  if (stored) pv_entries[at] = value;
  barrier();
  if (gl_LocalInvocationIndex == 0u) s_count += total;
  barrier();
  return stored ? at : ~0u;
}

void main() {
  uint tid = gl_LocalInvocationIndex;
  uint now = pv_frame() + 1u;
  uint budget = pv.flags.y;
  uint cascades = pv_cascades();
  uint per = pv_probes_per_cascade();
  if (tid < cascades) {
    // The volume's centre: the camera plus forward_offset of the cascade's width along the view.
    vec3 o, d;
    gib_camera_ray(vec2(gib_render_size()) * 0.5, o, d);
    float s = pv_spacing(tid);
    vec3 centre = o + normalize(d) * (pv.volume.y * float(pv.grid.x) * s);
    ivec3 origin = ivec3(floor(centre / s)) - pv_dims() / 2;
    s_origin[tid] = origin;
    pv_cascade[tid].origin = ivec4(origin, 0);
    pv_cascade[tid].rr.zw = uvec2(0u, 1u);
  }
  if (tid == 0u) s_count = 0u;
  barrier();

  // 1. New probes: slots whose cell changed (or never traced, or moved by relocation).
  uint fresh_total = 0u;
  for (uint base = 0u; base < cascades * per; base += kPvSelectGroup) {
    uint i = base + tid;
    bool fresh = false;
    if (i < cascades * per) {
      uint c = i / per;
      ivec3 cell = pv_cell_of_slot(s_origin[c], pv_slot_of_index(i % per));
      PvProbe p = pv_probes[i];
      uint f = uint(p.coord.w);
      if (any(notEqual(p.coord.xyz, cell))) {
        // The slot now holds another cell: nothing of its data is valid.
        pv_probes[i].coord = ivec4(cell, 0);
        pv_probes[i].offset = vec4(0.0, 0.0, 0.0, 1.0);
        pv_probes[i].geometry = vec4(0.0);
        f = 0u;
      }
      fresh = (f & kPvProbeTraced) == 0u;
    }
    append(fresh, i, budget);
    if (fresh && i < cascades * per) atomicAdd(pv_cascade[i / per].rr.z, 1u);
  }
  uint total_new = s_count;
  uint n_new = min(total_new, budget);
  for (uint k = tid; k < n_new; k += kPvSelectGroup) {
    uint i = pv_entries[k];
    pv_probes[i].stamp.xy = uvec2(now, kPvClassNew);
  }
  if (tid == 0u) s_count = n_new;
  memoryBarrierBuffer();
  barrier();

  // 2. G-buffer refreshes: first the probes probe_relocate moved (traced at their new offset),
  // in probe order, then round robin; 3. relight only, round robin. Round robin per cascade,
  // the biggest first, the class's share split evenly (remainders to the biggest).
  uint rest = budget - n_new;
  uint gbuffer_total = uint(floor(float(rest) * pv.sampling.w + 0.5));
  for (uint base = 0u; base < cascades * per; base += kPvSelectGroup) {
    uint i = base + tid;
    bool moved = false;
    if (i < cascades * per) {
      uint f = uint(pv_probes[i].coord.w);
      moved = (f & kPvProbeTraced) != 0u && (f & kPvProbeRetrace) != 0u && pv_probes[i].stamp.x != now;
    }
    append(moved, i, n_new + gbuffer_total);
  }
  uint n_moved = min(s_count, n_new + gbuffer_total) - n_new;
  for (uint k = n_new + tid; k < n_new + n_moved; k += kPvSelectGroup) pv_probes[pv_entries[k]].stamp.xy = uvec2(now, kPvClassGbuffer);
  memoryBarrierBuffer();
  barrier();
  if (tid == 0u) s_count = n_new + n_moved;
  barrier();
  uint totals[2] = uint[2](gbuffer_total - n_moved, rest - gbuffer_total);
  uint counts[2] = uint[2](n_moved, 0u);
  for (uint cls = 0u; cls < 2u; ++cls) {
    for (uint k = 0u; k < cascades; ++k) {
      uint c = cascades - 1u - k;
      uint share = totals[cls] / cascades + (k < totals[cls] % cascades ? 1u : 0u);
      share = min(share, per);
      uint start = cls == 0u ? pv_cascade[c].rr.x : pv_cascade[c].rr.y;
      uint first = s_count;
      uint limit = min(first + share, budget);
      // The window runs on past the probes it cannot take (selected already this frame, not
      // traced, or disabled for relighting) until it has its share or has seen the whole
      // cascade, and the index resumes after the last probe taken (the seed's round robin: "the
      // next frame the selection can start from the next probe"). A window of `share`
      // consecutive slots instead lost the slots another class had taken: with a budget of every
      // probe, some went unlit every other frame.
      if (tid == 0u) s_scanned = share > 0u ? per : 0u;
      barrier();
      for (uint j0 = 0u; j0 < per && share > 0u && s_count < limit; j0 += kPvSelectGroup) {
        uint j = j0 + tid;
        uint i = c * per + (start + j) % per;
        bool pick = false;
        if (j < per) {
          PvProbe p = pv_probes[i];
          uint f = uint(p.coord.w);
          pick = p.stamp.x != now && (f & kPvProbeTraced) != 0u && (cls == 0u || (f & kPvProbeDisabled) == 0u);
        }
        // The thread holding the window's last entry marks where the next frame starts.
        if (append(pick, i, limit) == limit - 1u) s_scanned = j + 1u;
        barrier();
      }
      uint last = min(s_count, limit);
      // The last block may have found more than the share: the next window appends after it.
      memoryBarrierBuffer();
      barrier();
      if (tid == 0u) s_count = last;
      for (uint e = first + tid; e < last; e += kPvSelectGroup)
        pv_probes[pv_entries[e]].stamp.xy = uvec2(now, cls == 0u ? kPvClassGbuffer : kPvClassRelight);
      memoryBarrierBuffer();
      barrier();
      if (tid == 0u) {
        counts[cls] += last - first;
        if (cls == 0u)
          pv_cascade[c].rr.x = (start + s_scanned) % per;
        else
          pv_cascade[c].rr.y = (start + s_scanned) % per;
      }
    }
  }
  if (tid == 0u) {
    uint traced = n_new + counts[0];
    uint all_selected = traced + counts[1];
    sel.traced_args = uvec4(traced, 1u, 1u, 0u);
    sel.all_args = uvec4(all_selected, 1u, 1u, 0u);
    sel.counts = uvec4(n_new, counts[0], counts[1], total_new - n_new);
  }
}
