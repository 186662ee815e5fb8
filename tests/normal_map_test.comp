#version 450
// GPU side of tests/test_normal_map.cpp: normal_map.glsl on the device, compared with the CPU
// mirror (renderer/scene/normal_map.h).
#extension GL_GOOGLE_include_directive : require

#include "tests/normal_map_test_shared.h"

layout(std430, binding = NORMAL_MAP_TEST_BINDING_QUERIES) readonly buffer Queries { float qw[]; };
layout(std430, binding = NORMAL_MAP_TEST_BINDING_OUT) writeonly buffer Out { NormalMapTestOut outs[]; };
layout(push_constant) uniform Push { NormalMapTestPush pc; };
layout(local_size_x = NORMAL_MAP_TEST_WORKGROUP_SIZE) in;

#include "normal_map.glsl"

vec3 q3(uint b) { return vec3(qw[b], qw[b + 1u], qw[b + 2u]); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  uint b = i * 22u;  // NormalMapTestQuery: 22 floats, read as words (std430 pads a struct of arrays)
  vec3 r = gib_normal_map(q3(b), q3(b + 4u), q3(b + 7u), q3(b + 10u), vec2(qw[b + 13u], qw[b + 14u]),
                          vec2(qw[b + 15u], qw[b + 16u]), vec2(qw[b + 17u], qw[b + 18u]), q3(b + 19u), qw[b + 3u]);
  NormalMapTestOut o;
  o.n = float[3](r.x, r.y, r.z);
  o.pad = 0.0;
  outs[i] = o;
}
