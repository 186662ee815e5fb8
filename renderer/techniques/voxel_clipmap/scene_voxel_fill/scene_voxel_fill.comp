// scene_voxel_fill: geometry opacity and coarser-level radiance for the voxels that entered the
// clipmap (see scene_voxel_fill.h); two kernels chosen by the specialisation constant kKernel.
// Opacities and source triangles merge with atomicMax of one key (vc_fill_key), so the result
// does not depend on thread order.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/scene_voxel_fill/scene_voxel_fill_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "finite.glsl"
layout(constant_id = kScFillSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kScFillBindState, )
VC_VOXEL_BUFFER(kScFillBindVoxels, )
VC_THIRD_BUFFER(kScFillBindThird, )
layout(std430, set = 0, binding = kScFillBindGeometry) buffer GeometryBuffer { uint geometry[]; };
#define VC_HAS_STATE
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
#include "renderer/techniques/voxel_clipmap/include/vc_voxelize.glsl"
layout(local_size_x = kScFillGroup) in;

void voxelize(uint tid) {
  uint tri = tid / vc_levels(), l = tid % vc_levels();
  if (tri >= gib_frame.scene_info.x) return;
  ivec4 o = vc_state.voxel_origin[l];
  if ((o.w & int(kVcOriginEntered)) == 0) return;
  GpuTriangle t = gib_triangles[tri];
  vec3 a = gib_vertices[t.i0].position, b = gib_vertices[t.i1].position, c = gib_vertices[t.i2].position;
  if (!gib_finite(a) || !gib_finite(b) || !gib_finite(c)) return;
  // Zero-area triangles are left out, as the BVH leaves them out (a removed instance, scene key
  // removed_at, is collapsed to a point and must not keep an opaque voxel there).
  if (all(equal(cross(b - a, c - a), vec3(0.0)))) return;
  GpuMaterial m = gib_materials[gib_instances[t.instance].material];
  float opacity = (m.alpha != GIB_ALPHA_NONE && vc_flag(kVcFlagSemiTransparent)) ? m.avg_opacity : 1.0;
  // The key keeps the triangle scene_voxel_light lights the voxel from (voxel_clipmap_shared.h).
  vec3 nrm = cross(b - a, c - a), an = abs(nrm);
  uint key = vc_fill_key(vc_opacity_byte(opacity), dot(nrm, gib_frame.camera_pos.xyz - a) > 0.0, tri);
  // One key per dominant axis of the normal: the merge keeps the best of all and the best of
  // another axis (a wall and the floor or ceiling it meets).
  uint axis = an.x >= an.y && an.x >= an.z ? 0u : (an.y >= an.z ? 1u : 2u);
  float s = vc_voxel_size(l);
  int n = vc_n();
  // Every voxel the triangle's bounds touch: voxel g spans [g s, (g + 1) s], so a triangle on a
  // voxel boundary also reaches the voxel below it (floor alone would test the one above only,
  // and a wall on the boundary at a room's far side would leave its inner voxel empty).
  ivec3 lo = max(ivec3(ceil(min(a, min(b, c)) / s)) - 1, o.xyz);
  ivec3 hi = min(ivec3(floor(max(a, max(b, c)) / s)), o.xyz + ivec3(n - 1));
  vec3 h = vec3(0.5 * s);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        ivec3 g = ivec3(x, y, z);
        uint idx = vc_voxel_index(l, g);
        if ((vc_voxels[idx].y & kVcVoxelNew) == 0u) continue;
        if (vc_triangle_box_overlap(a, b, c, (vec3(g) + 0.5) * s, h)) atomicMax(geometry[3u * idx + axis], key);
      }
}

void merge(uint tid) {
  if (tid >= vc_levels() * vc_voxels_per_level()) return;
  uvec4 v = vc_voxels[tid];
  if ((v.y & kVcVoxelNew) == 0u) return;
  uint l = tid / vc_voxels_per_level(), slot = tid % vc_voxels_per_level();
  int n = vc_n();
  ivec3 s = ivec3(int(slot) % n, (int(slot) / n) % n, int(slot) / (n * n));
  ivec3 g = vc_slot_world(s, vc_state.voxel_origin[l].xyz, n);
  uint radiance = 0u, emitted = 0u;
  if (l + 1u < vc_levels()) {
    // The coarser voxel holding this one's centre (grid coordinates halve per level).
    ivec3 gc = ivec3(floor((vec3(g) + 0.5) * 0.5));
    if (vc_in_box(gc, vc_state.voxel_origin[l + 1u].xyz, n)) {
      uvec4 cv = vc_voxels[vc_voxel_index(l + 1u, gc)];
      if ((cv.y & (kVcVoxelFed | kVcVoxelLit)) != 0u) {
        radiance = cv.x;
        emitted = cv.z;
      }
    }
  }
  // The best key of all (the triangle the voxel is lit from, its opacity), the best of the other
  // two axes and the remaining one (the planes the cube lookups' wall test sees).
  uvec3 keys = uvec3(geometry[3u * tid], geometry[3u * tid + 1u], geometry[3u * tid + 2u]);
  uint key = max(keys.x, max(keys.y, keys.z));
  uvec2 rest = keys.x == key ? keys.yz : (keys.y == key ? keys.xz : keys.xy);
  uint second = max(rest.x, rest.y), third = min(rest.x, rest.y);
  vc_voxel_third[tid] = third & kVcFillTriangleMask;
  uint y = kVcVoxelNew;
  if (key != 0u) {
    y |= kVcVoxelGeometry | (key >> 24);
    atomicAdd(vc_state.stats.z, 1u);
  }
  vc_voxels[tid] = vc_with_second_triangle(uvec4(radiance, y, emitted, key & kVcFillTriangleMask), second & kVcFillTriangleMask);
}

void main() {
  if (kKernel == kScFillVoxelize) voxelize(gl_GlobalInvocationID.x);
  else merge(gl_GlobalInvocationID.x);
}
