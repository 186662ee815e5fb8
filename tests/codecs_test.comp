#version 450
// GPU side of tests/test_codecs.cpp: the packing / octahedral / SH helpers on the device, for a
// bit-for-bit (packing) or tolerance (geometry) comparison with the CPU mirrors.
#extension GL_GOOGLE_include_directive : require

#include "tests/codecs_test_shared.h"
#include "packing.glsl"
#include "octahedral.glsl"
#include "sh.glsl"

layout(std430, binding = CODECS_TEST_BINDING_IN) readonly buffer In { uint words[]; };
layout(std430, binding = CODECS_TEST_BINDING_OUT) writeonly buffer Out { uint out_words[]; };
layout(push_constant) uniform Push { CodecsTestPush pc; };
layout(local_size_x = CODECS_TEST_WORKGROUP_SIZE) in;

void packing(uint i) {
  uvec4 w = uvec4(words[4 * i], words[4 * i + 1], words[4 * i + 2], words[4 * i + 3]);
  vec4 f = uintBitsToFloat(w);
  CodecsTestOut o;
  o.rgb9e5 = gib_pack_rgb9e5(f.xyz);
  o.r11g11b10 = gib_pack_r11g11b10(f.xyz);
  o.r11g11b10_rne = gib_pack_r11g11b10_rne(f.xyz);
  o.half_xy = gib_pack_half2x16(f.xy);
  o.half_zw = gib_pack_half2x16(f.zw);
  o.native_half_xy = packHalf2x16(f.xy);
  o.native_half_zw = packHalf2x16(f.zw);
  o.rgb9e5_dither = gib_pack_rgb9e5_dither(f.xyz, w.w);
  vec3 e5 = gib_unpack_rgb9e5(w.x);
  vec3 r11 = gib_unpack_r11g11b10(w.y);
  vec2 h = gib_unpack_half2x16(w.z);
  uint b = 18u * i;
  out_words[b + 0] = o.rgb9e5;
  out_words[b + 1] = o.r11g11b10;
  out_words[b + 2] = o.r11g11b10_rne;
  out_words[b + 3] = o.half_xy;
  out_words[b + 4] = o.half_zw;
  out_words[b + 5] = o.native_half_xy;
  out_words[b + 6] = o.native_half_zw;
  out_words[b + 7] = o.rgb9e5_dither;
  // Floats go out as bits, so no float store can canonicalise a NaN.
  out_words[b + 8] = floatBitsToUint(e5.x);
  out_words[b + 9] = floatBitsToUint(e5.y);
  out_words[b + 10] = floatBitsToUint(e5.z);
  out_words[b + 11] = floatBitsToUint(r11.x);
  out_words[b + 12] = floatBitsToUint(r11.y);
  out_words[b + 13] = floatBitsToUint(r11.z);
  out_words[b + 14] = floatBitsToUint(h.x);
  out_words[b + 15] = floatBitsToUint(h.y);
  out_words[b + 16] = gib_pack_half2x16_rtz(f.xy);
  out_words[b + 17] = gib_pack_half2x16_rtz(f.zw);
}

void geometry(uint i) {
  uint a = 8u * i;
  vec3 d = normalize(uintBitsToFloat(uvec3(words[a], words[a + 1], words[a + 2])));
  vec2 uv = uintBitsToFloat(uvec2(words[a + 3], words[a + 4]));
  ivec2 texel = ivec2(words[a + 5], words[a + 6]);
  int interior = int(words[a + 7]);
  vec2 e = gib_oct_encode(d);
  vec3 n = gib_oct_decode(uv);
  vec4 sh = vec4(uv, uintBitsToFloat(uvec2(words[a], words[a + 1])));
  float irr = gib_sh2_irradiance(sh, d);
  ivec2 s = gib_oct_border_source(texel, interior);
  vec4 basis = gib_sh2_basis(d);
  uint b = 12u * i;
  out_words[b + 0] = floatBitsToUint(e.x);
  out_words[b + 1] = floatBitsToUint(e.y);
  out_words[b + 2] = floatBitsToUint(n.x);
  out_words[b + 3] = floatBitsToUint(n.y);
  out_words[b + 4] = floatBitsToUint(n.z);
  out_words[b + 5] = floatBitsToUint(irr);
  out_words[b + 6] = uint(s.x);
  out_words[b + 7] = uint(s.y);
  out_words[b + 8] = floatBitsToUint(basis.x);
  out_words[b + 9] = floatBitsToUint(basis.y);
  out_words[b + 10] = floatBitsToUint(basis.z);
  out_words[b + 11] = floatBitsToUint(basis.w);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (pc.mode == CODECS_TEST_MODE_PACKING) packing(i);
  else geometry(i);
}
