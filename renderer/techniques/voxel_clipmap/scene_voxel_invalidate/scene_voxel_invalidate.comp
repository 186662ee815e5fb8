// scene_voxel_invalidate: clears the voxels and ages the cells overlapping the boxes of moved
// geometry (see scene_voxel_invalidate.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/scene_voxel_invalidate/scene_voxel_invalidate_shared.h"
layout(push_constant) uniform Push {
  VcParams vc;
  vec4 box_min[kScInvalidateMaxBoxes];
  vec4 box_max[kScInvalidateMaxBoxes];
  uvec4 count;
};
VC_STATE_BUFFER(kScInvalidateBindState, )
VC_VOXEL_BUFFER(kScInvalidateBindVoxels, )
layout(std430, set = 0, binding = kScInvalidateBindCells) buffer CellState { uint cell_state[]; };
#define VC_HAS_STATE
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kScInvalidateGroup) in;

// The grid box [g, g + 1) x size overlaps one of the changed boxes.
bool overlaps(ivec3 g, float size) {
  vec3 lo = vec3(g) * size, hi = lo + size;
  for (uint i = 0u; i < count.x; ++i)
    if (all(lessThan(lo, box_max[i].xyz)) && all(greaterThan(hi, box_min[i].xyz))) return true;
  return false;
}

void main() {
  uint tid = gl_GlobalInvocationID.x;
  bool voxels = count.y == 1u;
  uint per = voxels ? vc_voxels_per_level() : vc_cells_per_level();
  if (tid >= vc_levels() * per) return;
  uint l = tid / per, slot = tid % per;
  int n = voxels ? vc_n() : vc_m();
  ivec3 s = ivec3(int(slot) % n, (int(slot) / n) % n, int(slot) / (n * n));
  if (voxels) {
    ivec3 g = vc_slot_world(s, vc_state.voxel_origin[l].xyz, n);
    if (!overlaps(g, vc_voxel_size(l))) return;
    vc_voxels[tid] = uvec4(0u, kVcVoxelNew, 0u, 0u);
    atomicOr(vc_state.voxel_origin[l].w, int(kVcOriginEntered));
    atomicAdd(vc_state.stats.x, 1u);
  } else {
    ivec3 k = vc_slot_world(s, vc_state.cell_origin[l].xyz, n);
    if (!overlaps(k, vc_cell_size(l))) return;
    cell_state[tid] |= kVcAgeMask;
  }
}
