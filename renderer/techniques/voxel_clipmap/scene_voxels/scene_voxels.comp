// scene_voxels: moves each level's box with the camera and clears the voxels that entered it
// (see scene_voxels.h); two kernels chosen by the specialisation constant kKernel.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/scene_voxels/scene_voxels_shared.h"
#include "frame.glsl"
layout(constant_id = kScVoxelsSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kScVoxelsBindState, )
VC_VOXEL_BUFFER(kScVoxelsBindVoxels, )
#define VC_HAS_STATE
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kScVoxelsGroup) in;

void main() {
  uint tid = gl_GlobalInvocationID.x;
  if (kKernel == kScVoxelsOrigins) {
    if (tid == 0u) vc_state.stats.xyz = uvec3(0u);
    if (tid >= vc_levels()) return;
    ivec4 prev = vc_state.voxel_origin[tid];
    ivec3 o = vc_origin_around(gib_frame.camera_pos.xyz, vc_voxel_size(tid), vc_n());
    bool entered = (prev.w & int(kVcOriginValid)) == 0 || any(notEqual(prev.xyz, o));
    vc_state.voxel_prev[tid] = prev;
    vc_state.voxel_origin[tid] = ivec4(o, int(kVcOriginValid | (entered ? kVcOriginEntered : 0u)));
    return;
  }
  // kScVoxelsScroll
  if (tid >= vc_levels() * vc_voxels_per_level()) return;
  uint l = tid / vc_voxels_per_level();
  uint slot = tid % vc_voxels_per_level();
  uvec4 v = vc_voxels[tid];
  if ((v.y & kVcVoxelNew) != 0u) v.y &= ~kVcVoxelNew;  // last frame's entrants are ordinary voxels now
  ivec4 o = vc_state.voxel_origin[l], prev = vc_state.voxel_prev[l];
  if ((o.w & int(kVcOriginEntered)) != 0) {
    int n = vc_n();
    ivec3 s = ivec3(int(slot) % n, (int(slot) / n) % n, int(slot) / (n * n));
    ivec3 g = vc_slot_world(s, o.xyz, n);
    if ((prev.w & int(kVcOriginValid)) == 0 || !vc_in_box(g, prev.xyz, n)) {
      v = uvec4(0u, kVcVoxelNew, 0u, 0u);
      atomicAdd(vc_state.stats.x, 1u);
    }
  }
  vc_voxels[tid] = v;
}
