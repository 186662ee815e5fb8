#include "renderer/codecs/rgb9e5.h"

#include <algorithm>
#include <bit>

namespace gib::codecs {

namespace {
constexpr uint32_t kMaxBits = 0x477f8000u;  // 65408.0f

// Clamped channel as float bits: NaN, negatives -> 0; >= 65408 (incl. +Inf) -> 65408.
uint32_t clamp_bits(float f) {
  const uint32_t u = std::bit_cast<uint32_t>(f);
  if (u > 0x7f800000u) return 0;  // sign bit set (negatives, -0, -Inf, -NaN) or +NaN
  return std::min(u, kMaxBits);
}

// floor(c * 2^-unit_exp + 0.5) for the clamped channel with bits `u`, unit_exp = exp_s - 24.
uint32_t round_half_up(uint32_t u, int unit_exp) {
  if (u < 0x00800000u) return 0;  // zero or float denormal: < 2^-126, far below half a unit
  const uint32_t m = (u & 0x7fffffu) | 0x800000u;
  const int e = int(u >> 23) - 127 - 23;  // c = m * 2^e
  const int shift = unit_exp - e;         // >= 14 for clamped inputs (c < 2^(unit_exp + 10))
  if (shift > 24) return 0;               // c < 2^(unit_exp - 1): below half a unit
  return (m + (1u << (shift - 1))) >> shift;
}

// floor(c * 2^-unit_exp + dither * 2^-32): stochastic rounding.
uint32_t round_dither(uint32_t u, int unit_exp, uint32_t dither) {
  if (u < 0x00800000u) return 0;
  const uint32_t m = (u & 0x7fffffu) | 0x800000u;
  const int shift = unit_exp - (int(u >> 23) - 127 - 23);
  if (shift > 31) return 0;  // c < 2^(unit_exp - 7)
  return (m + (dither >> (32 - shift))) >> shift;
}
}  // namespace

uint32_t encode_rgb9e5_dither(const float rgb[3], uint32_t dither) {
  const uint32_t r = clamp_bits(rgb[0]), g = clamp_bits(rgb[1]), b = clamp_bits(rgb[2]);
  const uint32_t mx = std::max(r, std::max(g, b));
  int exp_shared = std::max(int(mx >> 23) - 127, -16) + 16;
  if (round_dither(mx, exp_shared - 24, 0xffffffffu) == 512u) exp_shared += 1;
  const int unit = exp_shared - 24;
  return round_dither(r, unit, dither) | (round_dither(g, unit, dither) << 9) | (round_dither(b, unit, dither) << 18) |
         (uint32_t(exp_shared) << 27);
}

uint32_t encode_rgb9e5(const float rgb[3]) {
  const uint32_t r = clamp_bits(rgb[0]), g = clamp_bits(rgb[1]), b = clamp_bits(rgb[2]);
  const uint32_t mx = std::max(r, std::max(g, b));  // bits of non-negative floats order like them
  // floor(log2(max)) from the exponent field; max(-16, .) makes every max < 2^-15 use exp' = 0.
  const int floor_log2 = std::max(int(mx >> 23) - 127, -16);
  int exp_shared = floor_log2 + 16;
  if (round_half_up(mx, exp_shared - 24) == 512u) exp_shared += 1;
  const int unit = exp_shared - 24;
  return round_half_up(r, unit) | (round_half_up(g, unit) << 9) | (round_half_up(b, unit) << 18) |
         (uint32_t(exp_shared) << 27);
}

}  // namespace gib::codecs
