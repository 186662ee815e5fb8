#version 450
// GPU side of tests/test_codecs.cpp (device formats): fetch the CPU-packed E5B9G9R9 and
// B10G11R11 texels through the sampler (the device's decode) and write floats through a
// B10G11R11 storage image (the device's encode).
#extension GL_GOOGLE_include_directive : require

#include "tests/codecs_test_shared.h"

layout(binding = CODECS_FORMAT_BINDING_E5) uniform sampler2D e5_image;
layout(binding = CODECS_FORMAT_BINDING_B10) uniform sampler2D b10_image;
layout(binding = CODECS_FORMAT_BINDING_STORE, r11f_g11f_b10f) uniform writeonly image2D store_image;
layout(binding = CODECS_FORMAT_BINDING_STORE16, rgba16f) uniform writeonly image2D store16_image;
layout(std430, binding = CODECS_FORMAT_BINDING_STORE_IN) readonly buffer StoreIn { vec4 store_in[]; };
layout(std430, binding = CODECS_FORMAT_BINDING_OUT) writeonly buffer Out { uint out_words[]; };
layout(push_constant) uniform Push { CodecsFormatPush pc; };
layout(local_size_x = CODECS_FORMAT_WORKGROUP, local_size_y = CODECS_FORMAT_WORKGROUP) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(pc.width) || p.y >= int(pc.height)) return;
  uint i = uint(p.y) * pc.width + uint(p.x);
  vec3 e5 = texelFetch(e5_image, p, 0).rgb;
  vec3 b10 = texelFetch(b10_image, p, 0).rgb;
  uint b = 8u * i;
  out_words[b + 0] = floatBitsToUint(e5.r);
  out_words[b + 1] = floatBitsToUint(e5.g);
  out_words[b + 2] = floatBitsToUint(e5.b);
  out_words[b + 3] = floatBitsToUint(b10.r);
  out_words[b + 4] = floatBitsToUint(b10.g);
  out_words[b + 5] = floatBitsToUint(b10.b);
  out_words[b + 6] = 0u;
  out_words[b + 7] = 0u;
  imageStore(store_image, p, vec4(store_in[i].xyz, 1.0));
  imageStore(store16_image, p, vec4(store_in[i].xyz, 1.0));
}
