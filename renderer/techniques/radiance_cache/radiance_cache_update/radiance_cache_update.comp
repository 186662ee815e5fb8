#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
layout(constant_id = kRcUpdateSpecKernel) const uint kKernel = kRcUpdateKernelInsert;

layout(local_size_x = kRcUpdateGroup) in;
layout(std430, set = 0, binding = kRcUpdateBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kRcUpdateBindActive) writeonly buffer ActiveBuffer { uint rc_active[]; };
layout(std430, set = 0, binding = kRcUpdateBindCounters) coherent buffer CounterBuffer { RcCounters counters; };
layout(push_constant) uniform Push { RcParams rc; uvec4 extra; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kRcUpdateBindCells, coherent)

const uint kNoCell = 0xffffffffu;

// The probe hit `id`'s committed key, or 0 for a miss / an id past the hit records.
uint hit_key(uint id) {
  uint rays = rc_rays_per_probe();
  if (id >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return 0u;
  ProbeHit h = probe_hits[id];
  if (h.triangle_plus1 == 0u) return 0u;
  uint probe = id / rays, ray = id - probe * rays;
  vec3 o = rc_probe_position(rc_updated_cascade(), rc_probe_coord(probe));
  vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));
  float lod;
  return rc_cell_key(rc_hit_position(o, d, h.distance), rc_facing_normal(h.triangle_plus1 - 1u, d), lod);
}

// Deterministic insertion (radiance_cache.glsl, "Insertion"): kernel `round` r = 0..max_probe-1
// lets every hit whose key is not yet in the table bid for slot first + r of its probe sequence;
// a bid is the key tagged with the round's parity (2 | r & 1) and the largest bid wins
// (atomicMax), so the winner depends on the set of keys, not on thread order. Kernel r first
// looks for the key in slots first .. first + r - 1 (settled by earlier rounds) and commits its
// own winning bid of round r - 1 (tag -> 1). The last kernel (r = max_probe) only settles: keys
// still unplaced are dropped, placed ones are queued for shading. Returns the hit's cell, or
// kNoCell when it is not placed (yet).
uint insert_round(uint key, uint round) {
  uint mask = rc_cell_mask(), first = rc_cell_first_slot(key), hash = key & ~3u;
  uint bid = hash | (2u + (round & 1u)), last_bid = hash | (2u + ((round + 1u) & 1u));
  for (uint s = 0u; s < round; ++s) {
    uint i = (first + s) & mask;
    uint v = rc_cells[i].key;
    if (v == key) return i;
    if (v == last_bid && s + 1u == round) {
      // Our bid of the previous round won: commit it (one of the key's hits counts it).
      if (atomicCompSwap(rc_cells[i].key, v, key) == v) atomicAdd(counters.insertions, 1u);
      return i;
    }
    if (s + 1u == round) atomicAdd(counters.collisions, 1u);  // passed last round's slot
  }
  if (round == rc_max_probe()) {
    atomicAdd(counters.drops, 1u);
    return kNoCell;
  }
  uint i = (first + round) & mask;
  uint v = rc_cells[i].key;
  if (v == key) return i;  // committed in an earlier frame
  // Empty, or holding this round's bids (same parity tag): bid. Anything else (a committed key or
  // the previous round's winner) is occupied: the next round tries the next slot.
  if (v == 0u || (v & 3u) == (bid & 3u)) atomicMax(rc_cells[i].key, bid);
  return kNoCell;
}

// After the last round: queue a placed hit's cell for shading unless it was shaded recently.
void queue_cell(uint cell) {
  uint now = rc.misc.x + 1u;
  uint shaded = atomicAdd(rc_cells[cell].shaded_frame, 0u);
  if (shaded == now) return;  // queued this frame by another hit
  if (shaded != 0u && now - shaded < rc.misc.y) {
    atomicAdd(counters.reused, 1u);
    return;
  }
  if (atomicCompSwap(rc_cells[cell].shaded_frame, shaded, now) != shaded) return;  // another hit won
  uint slot = atomicAdd(counters.active_cells, 1u);
  if (slot >= extra.x) return;  // unreachable: capacity >= hit records
  rc_active[slot] = cell;
  // Which of the cell's hits becomes its shading input is decided in the next kernel (lowest
  // hit id), not by who won this race: the same frame then shades the same way every run.
  rc_cells[cell].hit_index = 0xffffffffu;
}

void insert_hit(uint id) {
  uint key = hit_key(id);
  if (key == 0u) return;
  uint cell = insert_round(key, extra.y);
  if (extra.y == rc_max_probe() && cell != kNoCell) queue_cell(cell);
}

// Second kernel: every hit of a cell queued this frame offers its id; the smallest wins.
void pick_hit(uint id) {
  uint key = hit_key(id);
  if (key == 0u) return;
  uint cell = rc_find_cell(key);
  if (cell == kNoCell || rc_cells[cell].shaded_frame != rc.misc.x + 1u) return;
  atomicMin(rc_cells[cell].hit_index, id);
}

void main() {
  if (kKernel == kRcUpdateKernelInsert) {
    insert_hit(gl_GlobalInvocationID.x);
  } else if (kKernel == kRcUpdateKernelPick) {
    pick_hit(gl_GlobalInvocationID.x);
  } else if (gl_GlobalInvocationID.x == 0u) {
    uint queued = min(counters.active_cells, extra.x);
    counters.dispatch_x = (queued + kRcShadeGroup - 1u) / kRcShadeGroup;
    counters.dispatch_y = 1u;
    counters.dispatch_z = 1u;
  }
}
