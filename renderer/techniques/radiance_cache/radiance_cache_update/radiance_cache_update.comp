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

void insert_hit(uint id) {
  uint rays = rc_rays_per_probe();
  if (id >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return;
  ProbeHit h = probe_hits[id];
  if (h.triangle_plus1 == 0u) return;
  uint probe = id / rays, ray = id - probe * rays;
  uint c = rc_updated_cascade();
  vec3 o = rc_probe_position(c, rc_probe_coord(probe));
  vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));
  vec3 p = rc_hit_position(o, d, h.distance);
  float lod;
  uint key = rc_cell_key(p, rc_facing_normal(h.triangle_plus1 - 1u, d), lod);
  uint mask = rc_cell_mask(), first = rc_cell_first_slot(key), n = rc_max_probe();
  uint cell = kNoCell, steps = 0u;
  bool inserted = false;
  for (uint s = 0u; s < n; ++s) {
    uint i = (first + s) & mask;
    uint prev = atomicCompSwap(rc_cells[i].key, 0u, key);
    if (prev == 0u || prev == key) {
      cell = i;
      inserted = prev == 0u;
      break;
    }
    ++steps;
  }
  if (steps > 0u) atomicAdd(counters.collisions, steps);
  if (cell == kNoCell) {
    atomicAdd(counters.drops, 1u);
    return;
  }
  if (inserted) atomicAdd(counters.insertions, 1u);
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

// Second kernel: every hit of a cell queued this frame offers its id; the smallest wins.
void pick_hit(uint id) {
  uint rays = rc_rays_per_probe();
  if (id >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return;
  ProbeHit h = probe_hits[id];
  if (h.triangle_plus1 == 0u) return;
  uint probe = id / rays, ray = id - probe * rays;
  vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));
  vec3 p = rc_hit_position(rc_probe_position(rc_updated_cascade(), rc_probe_coord(probe)), d, h.distance);
  float lod;
  uint cell = rc_find_cell(rc_cell_key(p, rc_facing_normal(h.triangle_plus1 - 1u, d), lod));
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
