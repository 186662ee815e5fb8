#version 450
// GPU side of tests/test_textures_gpu.cpp: textures.glsl's fetch, bilinear filter and level
// selection on the device, compared bit for bit with the CPU mirror (renderer/scene/texture.h).
#extension GL_GOOGLE_include_directive : require

#include "tests/textures_test_shared.h"

layout(std430, binding = TEXTURES_TEST_BINDING_TEXTURES) readonly buffer Textures { uint gib_textures[]; };
layout(std430, binding = TEXTURES_TEST_BINDING_QUERIES) readonly buffer Queries { TexturesTestQuery queries[]; };
layout(std430, binding = TEXTURES_TEST_BINDING_OUT) writeonly buffer Out { TexturesTestOut outs[]; };
layout(push_constant) uniform Push { TexturesTestPush pc; };
layout(local_size_x = TEXTURES_TEST_WORKGROUP_SIZE) in;

#include "textures.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  TexturesTestQuery q = queries[i];
  vec2 uv = vec2(q.u, q.v), dx = vec2(q.dudx, q.dvdx), dy = vec2(q.dudy, q.dvdy);
  uvec4 b = floatBitsToUint(gib_texture_bilinear(q.texture, q.level, uv));
  uvec4 s = floatBitsToUint(gib_texture_sample(q.texture, uv, dx, dy));
  TexturesTestOut o;
  o.bilinear = uint[4](b.x, b.y, b.z, b.w);
  o.sampled = uint[4](s.x, s.y, s.z, s.w);
  o.level = gib_texture_level(q.texture, dx, dy);
  o.pad = uint[3](0u, 0u, 0u);
  outs[i] = o;
}
