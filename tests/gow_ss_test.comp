// gow-ragnarok's screen-space sampling pattern and surface encoding (gow_ss_pattern.glsl) on
// test inputs, for comparison with their CPU mirror (screen_space_pattern.h) in
// tests/test_gow_ssdo.cpp.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "tests/gow_ss_test_shared.h"
#include "hash.glsl"
#include "sampling.glsl"
#include "renderer/techniques/gow_ragnarok/include/gow_ss_pattern.glsl"
layout(push_constant) uniform Push { uvec4 count; };
layout(std430, set = 0, binding = kGowSsTestBindIn) readonly buffer InBuffer { GowSsTestIn items[]; };
layout(std430, set = 0, binding = kGowSsTestBindOut) writeonly buffer OutBuffer { GowSsTestOut results[]; };
layout(local_size_x = kGowSsTestGroup) in;

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= count.x) return;
  GowSsTestIn t = items[k];
  vec2 r = gow_ss_rotation(t.key.x, t.key.y, t.key.zw, t.index.x);
  results[k].rotation = vec4(r, 0.0, 0.0);
  results[k].direction = vec4(gow_ss_direction(t.index.y, t.index.z, r.x, t.normal.xyz), 0.0);
  uvec2 packed = gow_ss_pack_surface(t.surface.w, t.surface.xyz, t.index.w);
  GowSsSurface s = gow_ss_unpack_surface(packed);
  results[k].packed = uvec4(packed, s.pixel, s.plane ? 1u : 0u);
  results[k].unpacked = vec4(s.normal, s.dist);
}
