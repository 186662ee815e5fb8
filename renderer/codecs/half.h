// IEEE 754 binary16 ("half") conversion: the CPU mirror of the half helpers in
// renderer/shaders/include/packing.glsl (gib_float_to_half, gib_pack_half2x16, ...).
//
// float -> half: round to nearest, ties to even, with half denormals (|x| < 2^-14 keeps the
// bits a denormal can hold, rounded the same way). Sign is kept (also for 0, Inf and NaN).
// |x| >= 65520 (max finite 65504 plus half an ulp) rounds to Inf, as IEEE says. NaN -> the
// quiet NaN sign | 0x7e00 | (top 9 bits of the float payload): what x86 F16C (vcvtps2ph)
// and most GPUs produce, and never Inf. Float32 denormal inputs round to +-0. The rounding is
// done on the float's bits with integer arithmetic, so the GLSL version is exact on every
// device. It equals GLSL packHalf2x16 bit for bit on lavapipe and on NVIDIA H200 for every
// non-NaN input (tests/test_codecs.cpp, 4.2 million floats); for NaN inputs both devices give
// a NaN but their own payload bits. Vulkan leaves packHalf2x16's rounding open, hence our own.
//
// half -> float is exact: half_to_float() in packed_float.h (NaN -> quiet NaN).
#pragma once
#include <cstdint>

#include "renderer/codecs/packed_float.h"

namespace gib::codecs {

inline constexpr float kHalfMax = 65504.0f;

uint16_t float_to_half(float f);
// Same as float_to_half but rounding toward zero; overflow goes to the max finite value 65504,
// Inf stays Inf, NaN as above. For tests and comparisons with devices that truncate.
uint16_t float_to_half_rtz(float f);
// GLSL packHalf2x16 layout: a in bits 0-15, b in bits 16-31.
uint32_t pack_half2x16(float a, float b);
void unpack_half2x16(uint32_t packed, float out[2]);

// Shared by the small-float codecs (half, R11G11B10F): round the non-negative finite float
// with bits `abs_bits` (< 0x7f800000) to a float with 5 exponent bits (bias 15) and
// `mantissa_bits` mantissa bits, denormals included. Returns exponent << mantissa_bits |
// mantissa; a result >= 31 << mantissa_bits means the value overflowed (callers decide
// between Inf and the max finite value). to_nearest_even: true = RNE, false = toward zero.
uint32_t round_to_small_float(uint32_t abs_bits, uint32_t mantissa_bits, bool to_nearest_even);

}  // namespace gib::codecs
