// R11G11B10F (VK_FORMAT_B10G11R11_UFLOAT_PACK32: R bits 0-10, G 11-21, B 22-31; 5 exponent
// bits, bias 15; 6 / 6 / 5 mantissa bits; no sign): the CPU mirror of gib_pack_r11g11b10 /
// gib_unpack_r11g11b10 in renderer/shaders/include/packing.glsl.
//
// Encode policy (per channel), chosen to match what a shader's imageStore to a B10G11R11
// storage image does: on lavapipe bit for bit, on NVIDIA H200 for every non-NaN value (both
// truncate; tests/test_codecs.cpp, 1M texels):
// - rounding: toward zero (truncation of the dropped mantissa bits), denormals kept
//   (values below 2^-14 become denormals, below 2^-20 become 0). encode_r11g11b10_rne() is the
//   round-to-nearest-even alternative (half the error, no downward bias) for hand packing
//   where matching the hardware store does not matter.
// - negative values, -0 and -Inf -> 0.
// - finite values above the max finite 65024 (and, for RNE, those that would round up past
//   it) -> 65024: a finite input never becomes Inf.
// - +Inf -> Inf (exponent 31, mantissa 0).
// - NaN of either sign -> NaN: exponent 31 with the top mantissa bit set (0x7e0 for the 11-bit
//   channels, 0x3f0 for the 10-bit one), lavapipe's bits (NVIDIA stores all mantissa bits
//   set). NaN is kept rather than zeroed so that the harness's NaN counters still see it.
// Truncation biases every channel down by up to one ulp (2^-6 relative for R, G; 2^-5 for B),
// so it tints white toward yellow; encode_r11g11b10_rne halves the error and removes the bias.
// (vkCmdClearColorImage differs again: lavapipe's clear flushes values below 2^-14 to 0.)
// Decode is exact (decode_r11g11b10 in packed_float.h): denormals, Inf, NaN (quiet NaN).
#pragma once
#include <cstdint>

#include "renderer/codecs/packed_float.h"

namespace gib::codecs {

inline constexpr float kR11Max = 65024.0f;  // 11-bit channels (R, G)
inline constexpr float kB10Max = 64512.0f;  // 10-bit channel (B)

// One channel with `mantissa_bits` = 6 (R, G) or 5 (B): the 11- or 10-bit code.
uint32_t encode_ufloat_rtz(float f, uint32_t mantissa_bits);
uint32_t encode_ufloat_rne(float f, uint32_t mantissa_bits);

uint32_t encode_r11g11b10(const float rgb[3]);      // toward zero: the device store
uint32_t encode_r11g11b10_rne(const float rgb[3]);  // nearest even
inline uint32_t encode_r11g11b10(float r, float g, float b) {
  const float v[3] = {r, g, b};
  return encode_r11g11b10(v);
}

}  // namespace gib::codecs
