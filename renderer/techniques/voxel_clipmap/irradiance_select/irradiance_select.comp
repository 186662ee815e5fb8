// irradiance_select: ages every cell and queues this frame's cells to relight (see
// irradiance_select.h). One workgroup.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "renderer/techniques/voxel_clipmap/irradiance_select/irradiance_select_shared.h"
#include "frame.glsl"
#include "hash.glsl"
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kIrrSelectBindState, )
VC_VOXEL_BUFFER(kIrrSelectBindVoxels, readonly)
layout(std430, set = 0, binding = kIrrSelectBindCells) buffer CellState { uint cell_state[]; };
layout(std430, set = 0, binding = kIrrSelectBindQueue) buffer QueueBuffer {
  VcQueue queue;
  uint entries[];
};
#define VC_HAS_STATE
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kIrrSelectGroup) in;

shared uint s_subgroup[kIrrSelectGroup];
shared uint s_count[4];  // candidates so far: A', A, B, A out of view
shared uint s_passed;
shared uint s_passed_geometry;  // of them, cells with geometry

uint cap_total() { return vc.budget.y + vc.budget.w; }
// Scratch list q (0: A', 1: A, 2: B, 3: A out of view) after the final list.
uint scratch_base(uint q) {
  uint z = vc.budget.z, y = vc.budget.y, w = vc.budget.w;
  return cap_total() + (q == 0u ? 0u : (q == 1u ? z : (q == 2u ? z + y : z + y + w)));
}
uint scratch_cap(uint q) { return q == 0u ? vc.budget.z : (q == 1u || q == 3u ? vc.budget.y : vc.budget.w); }

// Appends `value` to scratch list q where `pred` (every thread calls it): thread order.
void append(bool pred, uint q, uint value) {
  uvec4 ballot = subgroupBallot(pred);
  if (subgroupElect()) s_subgroup[gl_SubgroupID] = subgroupBallotBitCount(ballot);
  barrier();
  uint before = s_count[q], total = 0u;
  for (uint i = 0u; i < gl_NumSubgroups; ++i) {
    if (i < gl_SubgroupID) before += s_subgroup[i];
    total += s_subgroup[i];
  }
  uint at = before + subgroupBallotExclusiveBitCount(ballot);
  if (pred && at < scratch_cap(q)) entries[scratch_base(q) + at] = value;
  barrier();
  if (gl_LocalInvocationIndex == 0u) s_count[q] += total;
  barrier();
}

// The cell's box holds a voxel with opacity (its 2x2x2 voxels of the same level).
bool has_geometry(uint l, ivec3 k) {
  for (int i = 0; i < 8; ++i) {
    ivec3 g = 2 * k + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    if (!vc_in_box(g, vc_voxel_origin(l), vc_n())) continue;
    if ((vc_voxels[vc_voxel_index(l, g)].y & kVcOpacityMask) != 0u) return true;
  }
  return false;
}

// Sphere of radius r around x against the frustum's side and near planes (rows of view_proj).
bool visible(vec3 x, float r) {
  mat4 m = gib_frame.view_proj;
  vec4 row0 = vec4(m[0][0], m[1][0], m[2][0], m[3][0]), row1 = vec4(m[0][1], m[1][1], m[2][1], m[3][1]);
  vec4 row2 = vec4(m[0][2], m[1][2], m[2][2], m[3][2]), row3 = vec4(m[0][3], m[1][3], m[2][3], m[3][3]);
  vec4 planes[5] = vec4[5](row3 + row0, row3 - row0, row3 + row1, row3 - row1, row2);
  for (int i = 0; i < 5; ++i)
    if (dot(planes[i].xyz, x) + planes[i].w < -r * length(planes[i].xyz)) return false;
  return true;
}

void main() {
  uint tid = gl_LocalInvocationIndex;
  if (tid < 4u) s_count[tid] = 0u;
  if (tid == 0u) s_passed = 0u;
  if (tid == 0u) s_passed_geometry = 0u;
  barrier();
  const bool per_queue = vc_flag(kVcFlagSelectPerQueue);
  // Cells with geometry out of view light the voxels scene_voxel_light keeps lit there (walls
  // behind the camera): they take what queue A's capacity the visible cells leave.
  const bool unseen = vc_flag(kVcFlagGeometryLight);
  float P = vc_state.select.x;
  float P_empty = per_queue ? vc_state.select.z : P;
  uint cells = vc_levels() * vc_cells_per_level();
  int m = vc_m();
  for (uint base = 0u; base < cells; base += kIrrSelectGroup) {
    uint cell = base + tid;
    bool real = cell < cells;
    bool qa_new = false, qa = false, qb = false, qa_out = false;
    if (real) {
      uint l = cell / vc_cells_per_level(), slot = cell % vc_cells_per_level();
      ivec3 s = ivec3(int(slot) % m, (int(slot) / m) % m, int(slot) / (m * m));
      ivec3 k = vc_slot_world(s, vc_cell_origin(l), m);
      uint st = cell_state[cell];
      uint age = min((st & kVcAgeMask) + 1u, kVcAgeMask);
      bool geometry = has_geometry(l, k);
      float c = vc_cell_size(l);
      bool vis = visible((vec3(k) + 0.5) * c, 0.87 * c);
      st = (st & ~(kVcAgeMask | kVcCellGeometry | kVcCellVisible)) | age | (geometry ? kVcCellGeometry : 0u) |
           (vis ? kVcCellVisible : 0u);
      cell_state[cell] = st;
      GibRng rng = gib_rng(vc.rays.z, vc_frame(), uvec2(cell, 7u), 11u);
      bool chance = float(age) * gib_next(rng) > (geometry ? P : P_empty);
      bool pass = vis && chance;
      qa_out = unseen && !vis && geometry && ((st & kVcCellRelit) == 0u || chance);
      qa_new = vis && geometry && (st & kVcCellRelit) == 0u;
      qa = pass && geometry && !qa_new;
      qb = pass && !geometry;
      if (qa || qb) atomicAdd(s_passed, 1u);
      if (qa) atomicAdd(s_passed_geometry, 1u);
    }
    append(qa_new, 0u, cell);
    append(qa, 1u, cell);
    append(qb, 2u, cell);
    append(qa_out, 3u, cell);
  }
  barrier();
  uint n_new = min(s_count[0], vc.budget.z);
  uint n_a = min(s_count[1], vc.budget.y - n_new);
  uint n_b = min(s_count[2], vc.budget.w);
  uint n_out = min(s_count[3], vc.budget.y - n_new - n_a);
  uint n = n_new + n_a + n_b + n_out;
  for (uint i = tid; i < n; i += kIrrSelectGroup) {
    uint src = i < n_new                     ? scratch_base(0u) + i
               : i < n_new + n_a             ? scratch_base(1u) + (i - n_new)
               : i < n_new + n_a + n_b       ? scratch_base(2u) + (i - n_new - n_a)
                                             : scratch_base(3u) + (i - n_new - n_a - n_b);
    entries[i] = entries[src];
  }
  if (tid == 0u) {
    queue.args = uvec4(n, 1u, 1u, 0u);
    queue.counts = uvec4(n_new, n_a, n_b, s_passed);
    // P for the next frame: towards passing about the queues' capacity (the seed's "chosen
    // based on the previous frame cells passed count").
    // select_per_queue: empty cells far outnumber cells with geometry, so one P tuned to the
    // queues' total capacity is set by empty cells that queue B mostly drops, and cells with
    // geometry starve; then each P follows its own queue's count and capacity.
    if (per_queue) {
      float ratio_a = clamp(float(s_passed_geometry) / float(max(vc.budget.y - n_new, 1u)), 0.5, 2.0);
      float ratio_b = clamp(float(s_passed - s_passed_geometry) / float(max(vc.budget.w, 1u)), 0.5, 2.0);
      vc_state.select = vec4(clamp(max(P, 0.01) * ratio_a, 0.01, 65535.0), float(s_passed),
                             clamp(max(P_empty, 0.01) * ratio_b, 0.01, 65535.0), 0.0);
    } else {
      float target = float(max(vc.budget.y - n_new, 1u) + vc.budget.w);
      float ratio = clamp(float(s_passed) / target, 0.5, 2.0);
      vc_state.select = vec4(clamp(max(P, 0.01) * ratio, 0.01, 65535.0), float(s_passed), 0.0, 0.0);
    }
  }
}
