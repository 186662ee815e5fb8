// Attribute encodings of the deferred technique (attribute_interpolate writes them, the
// texturing and lighting passes read them). CPU mirror and format notes:
// renderer/codecs/bary_deriv.h (bit for bit, tests/test_deferred.cpp).
#ifndef GIB_DEFERRED_ATTRIBUTES_GLSL
#define GIB_DEFERRED_ATTRIBUTES_GLSL
#include "packing.glsl"

const float kGibBaryDerivMax = 1.9990234375;
const uint kGibBaryDerivFlag = 0x4000u;

// Flag channels of the packed derivatives.
const uint kGibFlagFrontFacing = 0u;
const uint kGibFlagNormalNegZ = 1u;
const uint kGibFlagTangentNegZ = 2u;
const uint kGibFlagBitangentNeg = 3u;

uint gib_pack_bary_deriv(float d, bool flag) {
  // NaN compares false both ways: clamp(NaN) is undefined, so test on the bits first.
  if ((floatBitsToUint(d) & 0x7fffffffu) > 0x7f800000u) d = 0.0;
  d = clamp(d, -kGibBaryDerivMax, kGibBaryDerivMax);
  return gib_float_to_half(d) | (flag ? kGibBaryDerivFlag : 0u);
}
// Two derivatives at once (x in bits 0-15, y in 16-31), the same bits as gib_pack_bary_deriv
// of each: one conversion for the pair.
uint gib_pack_bary_deriv2(vec2 d, bool flag_x, bool flag_y) {
  bvec2 nan = greaterThan(floatBitsToUint(d) & 0x7fffffffu, uvec2(0x7f800000u));
  d = vec2(nan.x ? 0.0 : d.x, nan.y ? 0.0 : d.y);
  d = clamp(d, vec2(-kGibBaryDerivMax), vec2(kGibBaryDerivMax));
  return gib_pack_half2x16(d) | (flag_x ? kGibBaryDerivFlag : 0u) | (flag_y ? kGibBaryDerivFlag << 16 : 0u);
}
float gib_unpack_bary_deriv(uint packed) { return gib_half_to_float(packed & ~kGibBaryDerivFlag & 0xffffu); }
bool gib_bary_deriv_flag(uint packed) { return (packed & kGibBaryDerivFlag) != 0u; }

// v rounded to the nearest binary16 (ties to even), as a float. Stores to a 16-bit float image
// round as the device likes (Vulkan leaves it open; R11G11B10F stores truncate on lavapipe and
// NVIDIA): truncated, a normal's y of 0.99999994 becomes 0.99951 and its rebuilt z 0.031, a 1.8
// degree tilt; pre-rounded it is exactly 1 (z 0) on every device.
vec4 gib_round_to_half(vec4 v) {
  return vec4(gib_unpack_half2x16(gib_pack_half2x16(v.xy)), gib_unpack_half2x16(gib_pack_half2x16(v.zw)));
}
vec2 gib_round_to_half(vec2 v) { return gib_unpack_half2x16(gib_pack_half2x16(v)); }

float gib_unit_z_from_xy(float x, float y, bool negative) {
  precise float xy = x * x + y * y;
  float z = sqrt(max(0.0, 1.0 - xy));
  return negative ? -z : z;
}

#endif
