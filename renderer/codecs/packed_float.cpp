#include "renderer/codecs/packed_float.h"

#include <bit>
#include <cmath>

namespace gib::codecs {

float half_to_float(uint16_t h) {
  uint32_t sign = (h >> 15) & 1, e = (h >> 10) & 0x1F, m = h & 0x3FF;
  float v;
  if (e == 0) v = std::ldexp(float(m), -24);
  else if (e == 31) v = std::bit_cast<float>(0x7f800000u | (m << 13));  // Inf; NaN keeps its payload
  else v = std::ldexp(float(m | 0x400), int(e) - 25);
  return sign ? -v : v;
}

float ufloat_to_float(uint32_t bits, uint32_t mantissa_bits) {
  uint32_t m = bits & ((1u << mantissa_bits) - 1), e = bits >> mantissa_bits;
  if (e == 0) return std::ldexp(float(m), -14 - int(mantissa_bits));
  if (e == 31) return std::bit_cast<float>(0x7f800000u | (m << (23 - mantissa_bits)));  // Inf, NaN
  return std::ldexp(float(m | (1u << mantissa_bits)), int(e) - 15 - int(mantissa_bits));
}

void decode_r11g11b10(uint32_t p, float rgb[3]) {
  rgb[0] = ufloat_to_float(p & 0x7FF, 6);
  rgb[1] = ufloat_to_float((p >> 11) & 0x7FF, 6);
  rgb[2] = ufloat_to_float((p >> 22) & 0x3FF, 5);
}

void decode_rgb9e5(uint32_t p, float rgb[3]) {
  int e = int(p >> 27) - 15 - 9;
  rgb[0] = std::ldexp(float(p & 0x1FF), e);
  rgb[1] = std::ldexp(float((p >> 9) & 0x1FF), e);
  rgb[2] = std::ldexp(float((p >> 18) & 0x1FF), e);
}

}  // namespace gib::codecs
