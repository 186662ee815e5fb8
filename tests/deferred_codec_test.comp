#version 450
// GPU side of tests/test_deferred.cpp: the deferred technique's attribute packing on the device.
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/include/deferred_attributes.glsl"

layout(std430, binding = 0) readonly buffer In { uint words[]; };   // float bits, 2 per entry: value, flag
layout(std430, binding = 1) writeonly buffer Out { uint out_words[]; };  // packed, unpacked bits, z bits
layout(push_constant) uniform Push { uint count; };
layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  float v = uintBitsToFloat(words[2u * i]);
  bool flag = words[2u * i + 1u] != 0u;
  uint packed = gib_pack_bary_deriv(v, flag);
  // The pair form with entry i ^ 1 in the high half: its low half is this entry's word, its
  // high half the other entry's scalar word (bit 1 of the flag word set where it is not).
  uint j = min(i ^ 1u, count - 1u);
  float v2 = uintBitsToFloat(words[2u * j]);
  bool flag2 = words[2u * j + 1u] != 0u;
  uint pair = gib_pack_bary_deriv2(vec2(v, v2), flag, flag2);
  out_words[4u * i + 0u] = pair & 0xffffu;
  out_words[4u * i + 1u] = floatBitsToUint(gib_unpack_bary_deriv(packed));
  out_words[4u * i + 2u] = (gib_bary_deriv_flag(packed) ? 1u : 0u) | ((pair >> 16) == gib_pack_bary_deriv(v2, flag2) ? 0u : 2u);
  // z from (v / 2, v / 3) when that is inside the unit disc.
  out_words[4u * i + 3u] = floatBitsToUint(gib_unit_z_from_xy(v * 0.5, v * (1.0 / 3.0), flag));
}
