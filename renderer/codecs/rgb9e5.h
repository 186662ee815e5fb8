// RGB9E5 (VK_FORMAT_E5B9G9R9_UFLOAT_PACK32: R bits 0-8, G 9-17, B 18-26, shared exponent
// 27-31, bias 15, no implied leading one): the CPU mirror of gib_pack_rgb9e5 /
// gib_unpack_rgb9e5 in renderer/shaders/include/packing.glsl. Stored by hand in R32_UINT
// images (no device can write E5B9G9R9 from a shader); sampling the same bits as E5B9G9R9
// must decode identically (tests/test_codecs.cpp).
//
// Encode follows the Vulkan spec's shared-exponent conversion ("Shared Exponent" in the
// texel-conversion chapter; same as EXT_texture_shared_exponent):
//   c' = clamp(c, 0, 65408)          65408 = 511/512 * 2^16; NaN and negatives (-0, -Inf) -> 0,
//                                    +Inf and anything above -> 65408
//   exp' = max(-16, floor(log2(max(r', g', b')))) + 16
//   max_s = floor(max' / 2^(exp' - 24) + 0.5); if max_s == 512: exp_s = exp' + 1 else exp'
//   r_s = floor(r' / 2^(exp_s - 24) + 0.5)   (round half up), same for g, b
// computed with integer arithmetic on the float bits, so it is exact (no float rounding in
// "x + 0.5") on the CPU and on every GPU. Decode: c = c_s * 2^(exp - 24), exact.
#pragma once
#include <cstdint>

#include "renderer/codecs/packed_float.h"  // decode_rgb9e5

namespace gib::codecs {

inline constexpr float kRgb9e5Max = 65408.0f;

uint32_t encode_rgb9e5(const float rgb[3]);
inline uint32_t encode_rgb9e5(float r, float g, float b) {
  const float v[3] = {r, g, b};
  return encode_rgb9e5(v);
}

// Stochastic rounding (gib_pack_rgb9e5_dither): r_s = floor(r' / 2^(exp_s - 24) + dither / 2^32),
// same for g, b (channels below 2^-7 units give 0); exp_s is the smallest exponent whose largest
// channel cannot reach 512 for any dither. Over uniform dither the decoded value's expectation is
// the clamped input, which keeps a temporal filter's store unbiased.
uint32_t encode_rgb9e5_dither(const float rgb[3], uint32_t dither);

}  // namespace gib::codecs
