// irradiance_clipmap: moves each level's cell box with the camera; cells that entered start
// from the coarser level (see irradiance_clipmap.h). Two kernels chosen by kKernel.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/irradiance_clipmap/irradiance_clipmap_shared.h"
#include "frame.glsl"
layout(constant_id = kIrrClipmapSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kIrrClipmapBindState, )
VC_CUBE_BUFFERS(kIrrClipmapBindX, kIrrClipmapBindY, kIrrClipmapBindZ, kIrrClipmapBindCells, )
#define VC_HAS_STATE
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kIrrClipmapGroup) in;

bool entered(ivec3 k, uint l) {
  ivec4 prev = vc_state.cell_prev[l];
  return (prev.w & int(kVcOriginValid)) == 0 || !vc_in_box(k, prev.xyz, vc_m());
}

void main() {
  uint tid = gl_GlobalInvocationID.x;
  if (kKernel == kIrrClipmapOrigins) {
    if (tid == 0u) vc_state.stats.w = 0u;
    if (tid >= vc_levels()) return;
    ivec4 prev = vc_state.cell_origin[tid];
    ivec3 o = vc_origin_around(gib_frame.camera_pos.xyz, vc_cell_size(tid), vc_m());
    bool moved = (prev.w & int(kVcOriginValid)) == 0 || any(notEqual(prev.xyz, o));
    vc_state.cell_prev[tid] = prev;
    vc_state.cell_origin[tid] = ivec4(o, int(kVcOriginValid | (moved ? kVcOriginEntered : 0u)));
    return;
  }
  // kIrrClipmapScroll
  if (tid >= vc_levels() * vc_cells_per_level()) return;
  uint l = tid / vc_cells_per_level(), slot = tid % vc_cells_per_level();
  if ((vc_state.cell_origin[l].w & int(kVcOriginEntered)) == 0) return;
  int m = vc_m();
  ivec3 s = ivec3(int(slot) % m, (int(slot) / m) % m, int(slot) / (m * m));
  ivec3 k = vc_slot_world(s, vc_state.cell_origin[l].xyz, m);
  if (!entered(k, l)) return;
  atomicAdd(vc_state.stats.w, 1u);
  uint state = kVcAgeMask;
  uint src = 0xffffffffu;
  if (l + 1u < vc_levels()) {
    ivec3 kc = ivec3(floor((vec3(k) + 0.5) * 0.5));
    if (vc_in_box(kc, vc_state.cell_origin[l + 1u].xyz, m) && !entered(kc, l + 1u)) {
      uint c = vc_cell_index(l + 1u, kc);
      if ((vc_cell_state[c] & kVcCellUpdated) != 0u) src = c;
    }
  }
  if (src != 0xffffffffu) state |= kVcCellUpdated;
  for (uint i = 0u; i < kVcCellFloats; ++i) {
    uint d = tid * kVcCellFloats + i, c = src * kVcCellFloats + i;
    vc_cube_x[d] = src != 0xffffffffu ? vc_cube_x[c] : 0.0;
    vc_cube_y[d] = src != 0xffffffffu ? vc_cube_y[c] : 0.0;
    vc_cube_z[d] = src != 0xffffffffu ? vc_cube_z[c] : 0.0;
  }
  vc_cell_state[tid] = state;
}
