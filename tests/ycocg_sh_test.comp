#version 450
// GPU side of tests/test_probe_volume.cpp: the YCoCg SH codec (renderer/codecs/ycocg_sh.h).
#extension GL_GOOGLE_include_directive : require
#include "ycocg_sh.glsl"

layout(std430, binding = 0) readonly buffer In { uint words[]; };   // 6 float bits per entry
layout(std430, binding = 1) writeonly buffer Out { uint out_words[]; };  // 2 packed + 6 unpacked float bits
layout(push_constant) uniform Push { uint count; };
layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  float v[6];
  for (uint k = 0u; k < 6u; ++k) v[k] = uintBitsToFloat(words[6u * i + k]);
  uvec2 w = gib_pack_ycocg_sh(v[0], vec3(v[1], v[2], v[3]), vec2(v[4], v[5]));
  float y0;
  vec3 y1;
  vec2 cocg;
  gib_unpack_ycocg_sh(w, y0, y1, cocg);
  out_words[8u * i + 0u] = w.x;
  out_words[8u * i + 1u] = w.y;
  out_words[8u * i + 2u] = floatBitsToUint(y0);
  out_words[8u * i + 3u] = floatBitsToUint(y1.x);
  out_words[8u * i + 4u] = floatBitsToUint(y1.y);
  out_words[8u * i + 5u] = floatBitsToUint(y1.z);
  out_words[8u * i + 6u] = floatBitsToUint(cocg.x);
  out_words[8u * i + 7u] = floatBitsToUint(cocg.y);
}
