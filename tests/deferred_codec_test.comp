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
  out_words[4u * i + 0u] = packed;
  out_words[4u * i + 1u] = floatBitsToUint(gib_unpack_bary_deriv(packed));
  out_words[4u * i + 2u] = gib_bary_deriv_flag(packed) ? 1u : 0u;
  // z from (v / 2, v / 3) when that is inside the unit disc.
  out_words[4u * i + 3u] = floatBitsToUint(gib_unit_z_from_xy(v * 0.5, v * (1.0 / 3.0), flag));
}
