// CPU decoders of the GPU's packed float formats (used for readback and by tests).
// Bit layouts follow the Vulkan spec: B10G11R11_UFLOAT_PACK32 stores R in bits 0-10,
// G in 11-21, B in 22-31; E5B9G9R9_UFLOAT_PACK32 stores R 0-8, G 9-17, B 18-26, E 27-31.
// All decodes are exact, bit for bit what packing.glsl's gib_unpack_* return: a NaN keeps its
// sign and payload (shifted into the float's top mantissa bits). Encoders: rgb9e5.h,
// r11g11b10.h, half.h.
#pragma once
#include <cstdint>

namespace gib::codecs {

float half_to_float(uint16_t h);
// Unsigned small floats with 5 exponent bits and `mantissa_bits` (6 or 5) mantissa bits.
float ufloat_to_float(uint32_t bits, uint32_t mantissa_bits);
void decode_r11g11b10(uint32_t packed, float rgb[3]);
void decode_rgb9e5(uint32_t packed, float rgb[3]);

}  // namespace gib::codecs
