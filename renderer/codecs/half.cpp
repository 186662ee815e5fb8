#include "renderer/codecs/half.h"

#include <bit>

namespace gib::codecs {

uint32_t round_to_small_float(uint32_t a, uint32_t mbits, bool rne) {
  const int e = int(a >> 23) - 127;  // unbiased exponent (float denormals: -127, they round to 0)
  uint32_t m = (a & 0x7fffffu) | 0x800000u;  // 24-bit significand with its leading one
  if (e < -127 + 1) m = a & 0x7fffffu;        // float denormal: no leading one
  // The small float's value unit at this exponent: normal numbers keep mbits fraction bits
  // below the leading one; below 2^-14 the unit is fixed at 2^(-14 - mbits) (denormals).
  uint32_t exp_field;
  int shift;  // significand bits to drop
  if (e >= -14) {
    exp_field = uint32_t(e + 15);
    shift = 23 - int(mbits);
  } else {
    exp_field = 0;
    shift = 23 - int(mbits) + (-14 - e);
  }
  if (shift > 25) return 0;  // far below half the smallest denormal: rounds to 0 either way
  const uint32_t kept = m >> shift;
  const uint32_t rest = m & ((1u << shift) - 1u);
  const uint32_t half = 1u << (shift - 1);
  // Normal results store the fraction without its leading one; exponent and fraction added as
  // integers carry correctly when rounding overflows the fraction (into the next exponent).
  uint32_t bits = exp_field == 0 ? kept : ((exp_field << mbits) + (kept - (1u << mbits)));
  if (rne && (rest > half || (rest == half && (kept & 1u)))) bits += 1u;
  return bits;
}

namespace {
uint16_t to_half(float f, bool rne) {
  const uint32_t u = std::bit_cast<uint32_t>(f);
  const uint32_t sign = (u >> 16) & 0x8000u;
  const uint32_t a = u & 0x7fffffffu;
  if (a > 0x7f800000u) return uint16_t(sign | 0x7e00u | ((a >> 13) & 0x1ffu));  // NaN
  if (a == 0x7f800000u) return uint16_t(sign | 0x7c00u);                          // Inf
  uint32_t h = round_to_small_float(a, 10, rne);
  if (h >= 0x7c00u) h = rne ? 0x7c00u : 0x7bffu;  // overflow: Inf (RNE) or max finite (RTZ)
  return uint16_t(sign | h);
}
}  // namespace

uint16_t float_to_half(float f) { return to_half(f, true); }
uint16_t float_to_half_rtz(float f) { return to_half(f, false); }

uint32_t pack_half2x16(float a, float b) {
  return uint32_t(float_to_half(a)) | (uint32_t(float_to_half(b)) << 16);
}

void unpack_half2x16(uint32_t p, float out[2]) {
  out[0] = half_to_float(uint16_t(p & 0xffffu));
  out[1] = half_to_float(uint16_t(p >> 16));
}

}  // namespace gib::codecs
