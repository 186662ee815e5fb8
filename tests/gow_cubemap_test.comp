#version 450
// GPU side of tests/test_gow_reflections.cpp: gow_cubemap.glsl on the device, compared with the
// CPU mirror (renderer/techniques/gow_ragnarok/gow_cubemap.h).
#extension GL_GOOGLE_include_directive : require

#include "tests/gow_cubemap_test_shared.h"

layout(std430, binding = GOW_CUBEMAP_TEST_BINDING_QUERIES) readonly buffer Queries { float qw[]; };
layout(std430, binding = GOW_CUBEMAP_TEST_BINDING_OUT) writeonly buffer Out { uint ow[]; };
layout(push_constant) uniform Push { GowCubemapTestPush pc; };
layout(local_size_x = GOW_CUBEMAP_TEST_WORKGROUP_SIZE) in;

#include "renderer/techniques/gow_ragnarok/include/gow_cubemap.glsl"

vec3 q3(uint b) { return vec3(qw[b], qw[b + 1u], qw[b + 2u]); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  uint b = i * GOW_CUBEMAP_TEST_QUERY_FLOATS;
  vec3 x = q3(b), d = q3(b + 3u), bmin = q3(b + 6u), bmax = q3(b + 9u), capture = q3(b + 12u);
  ivec2 t = gow_cube_texel(d, uint(qw[b + 15u]));
  vec3 p = gow_box_project(x, d, bmin, bmax, capture);
  uint o = i * GOW_CUBEMAP_TEST_OUT_WORDS;
  ow[o] = uint(t.x);
  ow[o + 1u] = uint(t.y);
  ow[o + 2u] = floatBitsToUint(p.x);
  ow[o + 3u] = floatBitsToUint(p.y);
  ow[o + 4u] = floatBitsToUint(p.z);
  ow[o + 5u] = floatBitsToUint(gow_box_exit(x, d, bmin, bmax));
  ow[o + 6u] = 0u;
  ow[o + 7u] = 0u;
}
