// The voxel-clipmap GLSL (vc_common.glsl, vc_voxelize.glsl) on test inputs, for comparison
// with its CPU mirror (renderer/codecs/voxel_clipmap.h) in tests/test_voxel_clipmap.cpp.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "tests/voxel_clipmap_test_shared.h"
layout(push_constant) uniform Push {
  VcParams vc;
  uvec4 mode;
};
VC_STATE_BUFFER(kVcTestBindState, readonly)
VC_CUBE_BUFFERS(kVcTestBindX, kVcTestBindY, kVcTestBindZ, kVcTestBindCells, readonly)
layout(std430, set = 0, binding = kVcTestBindIn) readonly buffer InBuffer { VcTestIn items[]; };
layout(std430, set = 0, binding = kVcTestBindOut) writeonly buffer OutBuffer { VcTestOut results[]; };
#define VC_HAS_STATE
#define VC_HAS_CUBES
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
#include "renderer/techniques/voxel_clipmap/include/vc_voxelize.glsl"
layout(local_size_x = kVcTestGroup) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= mode.y) return;
  VcTestIn t = items[i];
  VcTestOut r;
  r.u = uvec4(0u);
  r.i = ivec4(0);
  r.f0 = vec4(0.0);
  r.f1 = vec4(0.0);
  if (mode.x == kVcTestAddressing) {
    uint l = uint(t.a.w);
    ivec3 o = floatBitsToInt(t.p0.xyz);
    int slot = floatBitsToInt(t.p0.w);
    int n = vc_n();
    ivec3 s = ivec3(slot % n, (slot / n) % n, slot / (n * n));
    r.u = uvec4(vc_voxel_index(l, t.a.xyz), vc_slot_index(vc_wrap(t.a.xyz, n), n), vc_in_box(t.a.xyz, o, n) ? 1u : 0u, 0u);
    r.i = ivec4(vc_slot_world(s, o, n), 0);
  } else if (mode.x == kVcTestLevel) {
    r.u.x = vc_voxel_level(t.p0.xyz);
    r.i = ivec4(vc_origin_around(t.p0.xyz, vc_voxel_size(1u), vc_n()), 0);
  } else if (mode.x == kVcTestCube) {
    vec3 b, s;
    float h;
    vc_cube_eval(uint(t.a.x), t.p0.xyz, b, s, h);
    r.f0 = vec4(b, h);
    r.f1 = vec4(s, 0.0);
  } else if (mode.x == kVcTestOverlap) {
    r.u.x = vc_triangle_box_overlap(t.p0.xyz, t.p1.xyz, t.p2.xyz, t.p3.xyz, vec3(t.p3.w)) ? 1u : 0u;
  } else if (mode.x == kVcTestFillKey) {
    r.u.x = vc_fill_key(uint(t.a.x), t.a.y != 0, uint(t.a.z));
  } else if (mode.x == kVcTestSecond) {
    uvec4 v = vc_with_second_triangle(uvec4(0u, uint(t.a.x), 0u, uint(t.a.y)), uint(t.a.z));
    r.u = uvec4(vc_second_triangle(uvec4(0u, uint(t.a.x), 0u, uint(t.a.y))), v.y, v.w, vc_second_triangle(v));
  } else if (mode.x == kVcTestVisStep) {
    r.u.x = vc_vis_row_step(uint(t.a.x), uint(t.a.y), uint(t.a.z), uint(t.a.w), uint(floatBitsToInt(t.p0.x)), uint(floatBitsToInt(t.p0.y)));
  } else if (mode.x == kVcTestVisBit) {
    r.i.x = vc_vis_bit(t.a.xyz, floatBitsToInt(t.p0.xyz));
  } else if (mode.x == kVcTestClosest) {
    r.f0 = vec4(vc_closest_on_triangle(t.p3.xyz, t.p0.xyz, t.p1.xyz, t.p2.xyz), 0.0, 0.0);
  } else {
    r.u.x = vc_opacity_byte(t.p0.w);
  }
  results[i] = r;
}
