// Packed float formats by hand (owner: codecs). CPU mirrors in renderer/codecs/ (rgb9e5.h,
// r11g11b10.h, half.h) agree bit for bit (tests/test_codecs.cpp); their headers state the
// policies. Everything is integer arithmetic on float bits (the half conversion's fast path
// excepted, see below), so the result does not depend on a device's float rounding, denormal
// flushing or NaN handling in min/max.
//
// RGB9E5 (E5B9G9R9_UFLOAT_PACK32 layout, stored in R32_UINT images): Vulkan spec shared
// exponent, round half up; NaN / negatives -> 0; clamp to 65408.
//   uint gib_pack_rgb9e5(vec3 rgb); vec3 gib_unpack_rgb9e5(uint p);
// gib_pack_rgb9e5_dither(rgb, dither): stochastic rounding, floor(c / unit + dither / 2^32), for
// stores that blend with their own last value (see the function).
// R11G11B10F (B10G11R11_UFLOAT_PACK32 layout): rounding toward zero, like an imageStore to a
// B10G11R11 image on lavapipe and NVIDIA; negatives -> 0; finite above max -> max finite
// (65024 / 64512); +Inf -> Inf; NaN -> NaN (0x7e0 / 0x3f0). gib_pack_r11g11b10_rne rounds to
// nearest even (no downward bias).
//   uint gib_pack_r11g11b10(vec3 rgb); uint gib_pack_r11g11b10_rne(vec3 rgb);
//   vec3 gib_unpack_r11g11b10(uint p);
// Half (IEEE binary16): round to nearest even with denormals, overflow -> Inf, NaN -> quiet
// NaN with the sign and top payload bits. Equal to packHalf2x16 on lavapipe and NVIDIA for all
// non-NaN inputs (Vulkan leaves packHalf2x16's rounding open; these are exact everywhere).
// gib_float_to_half corrects the device's packHalf2x16 to RNE on normal halves (exact wherever
// packHalf2x16 returns one of the two halves around the value, as gib_pack_half2x16_rtz needs);
// gib_float_to_half_exact is integer arithmetic throughout.
//   uint gib_float_to_half(float f); uint gib_float_to_half_exact(float f); float gib_half_to_float(uint h);
//   uint gib_pack_half2x16(vec2 v); vec2 gib_unpack_half2x16(uint p);
// gib_pack_half2x16_rtz(v): packHalf2x16 layout, rounding toward zero (overflow -> 65504, Inf
// stays Inf, NaN stays NaN): what an imageStore to an RGBA16F image gives on lavapipe; a value so
// rounded is stored exactly by any device. Cheap (the device's packHalf2x16, then one step
// toward zero where it rounded away): exact wherever packHalf2x16 returns one of the two halves
// around the value with denormals (RNE on lavapipe and NVIDIA, tests/test_codecs.cpp).
#ifndef GIB_PACKING_GLSL
#define GIB_PACKING_GLSL
#include "device_spec_shared.h"

// Round the non-negative finite float with bits a (< 0x7f800000) to a small float with 5
// exponent bits (bias 15) and mbits mantissa bits, denormals included. Returns
// exponent << mbits | mantissa; >= 31 << mbits means overflow. rne: nearest even, else toward 0.
uint gib_round_to_small_float(uint a, uint mbits, bool rne) {
  int e = int(a >> 23) - 127;
  uint m = (e < -126) ? (a & 0x7fffffu) : ((a & 0x7fffffu) | 0x800000u);
  uint exp_field;
  int shift;
  if (e >= -14) {
    exp_field = uint(e + 15);
    shift = 23 - int(mbits);
  } else {
    exp_field = 0u;
    shift = 23 - int(mbits) + (-14 - e);
  }
  if (shift > 25) return 0u;
  uint kept = m >> uint(shift);
  uint rest = m & ((1u << uint(shift)) - 1u);
  uint half_unit = 1u << uint(shift - 1);
  uint bits = (exp_field == 0u) ? kept : ((exp_field << mbits) + (kept - (1u << mbits)));
  if (rne && (rest > half_unit || (rest == half_unit && (kept & 1u) != 0u))) bits += 1u;
  return bits;
}

// ---- half
// The reference conversion, integer arithmetic only (any value, NaN and denormals included).
uint gib_float_to_half_exact(float f) {
  uint u = floatBitsToUint(f);
  uint sign = (u >> 16) & 0x8000u;
  uint a = u & 0x7fffffffu;
  if (a > 0x7f800000u) return sign | 0x7e00u | ((a >> 13) & 0x1ffu);
  if (a == 0x7f800000u) return sign | 0x7c00u;
  uint h = gib_round_to_small_float(a, 10u, true);
  return sign | min(h, 0x7c00u);
}

// The same bits as gib_float_to_half_exact, cheaper: where the value rounds to a normal half
// (2^-14 <= |f| <= 65504) the device's packHalf2x16 gives one of the two halves around it in
// whatever mode it rounds (RNE on lavapipe and NVIDIA), and one comparison of the two distances
// (exact: the value and a half one step away differ by at most a factor 2) picks the nearer,
// ties to the even code. Below 2^-14 the half is a multiple of 2^-24: roundEven(|f| 2^24) (an
// exact product) is its code, 0x400 where it rounds up to the smallest normal. Overflow, Inf and
// NaN take the exact path. Every common value thus takes a few instructions: where a warp mixed
// the integer path (tiny derivatives, normals' near-zero components) with the fast one, it paid
// for both.
// Where the device's packHalf2x16 rounds to nearest even (probed when the device is created,
// renderer/vk/gpu.cpp: lavapipe and NVIDIA do), its result is returned as is, without the
// correction below (renderer/techniques/deferred/deferred.md, "Cost", measures both).
layout(constant_id = kGibSpecNativeHalfRne) const bool kGibNativeHalfRne = false;

uint gib_float_to_half(float f) {
  float a = abs(f);
  uint sign = floatBitsToUint(f) >> 16 & 0x8000u;
  if (!(a <= 65504.0)) return gib_float_to_half_exact(f);
  if (kGibNativeHalfRne) return packHalf2x16(vec2(f, 0.0)) & 0xffffu;
  if (a < 6.103515625e-05) return sign | uint(roundEven(a * 16777216.0));
  uint h = packHalf2x16(vec2(a, 0.0)) & 0x7fffu;
  float got = unpackHalf2x16(h).x;
  if (got != a) {
    uint lo = got < a ? h : h - 1u;
    float below = unpackHalf2x16(lo).x, above = unpackHalf2x16(lo + 1u).x;
    float d_lo = a - below, d_hi = above - a;
    h = (d_lo < d_hi || (d_lo == d_hi && (lo & 1u) == 0u)) ? lo : lo + 1u;
  }
  return sign | h;
}

float gib_half_to_float(uint h) {
  uint sign = (h & 0x8000u) << 16;
  uint e = (h >> 10) & 0x1fu;
  uint m = h & 0x3ffu;
  if (e == 31u) return uintBitsToFloat(sign | 0x7f800000u | (m << 13));  // Inf, NaN
  if (e == 0u) {
    // Denormal: m * 2^-24, exact (a normal float); the sign goes on last so -0 stays -0.
    float v = float(m) * uintBitsToFloat(0x33800000u);
    return uintBitsToFloat(sign | floatBitsToUint(v));
  }
  return uintBitsToFloat(sign | ((e + 112u) << 23) | (m << 13));
}

uint gib_pack_half2x16(vec2 v) {
  // One packHalf2x16 for both where the device rounds to nearest even (Inf, NaN and overflow
  // take the per-value path for their policy).
  if (kGibNativeHalfRne && all(lessThanEqual(abs(v), vec2(65504.0)))) return packHalf2x16(v);
  return gib_float_to_half(v.x) | (gib_float_to_half(v.y) << 16);
}
uint gib_pack_half2x16_rtz(vec2 v) {
  uint p = packHalf2x16(v);
  vec2 back = unpackHalf2x16(p);
  // One code down is one step toward zero in the sign-magnitude layout (false for NaN).
  if (abs(back.x) > abs(v.x)) p -= 1u;
  if (abs(back.y) > abs(v.y)) p -= 0x10000u;
  return p;
}
vec2 gib_unpack_half2x16(uint p) {
  // Normal halves and zeros convert exactly on any device (unpackHalf2x16); denormals, which a
  // device may flush, Inf and NaN (their payload) take the integer path.
  uint lo = p & 0x7fffu, hi = (p >> 16) & 0x7fffu;
  bool lo_plain = lo == 0u || (lo >= 0x0400u && lo < 0x7c00u);
  bool hi_plain = hi == 0u || (hi >= 0x0400u && hi < 0x7c00u);
  if (lo_plain && hi_plain) return unpackHalf2x16(p);
  return vec2(gib_half_to_float(p & 0xffffu), gib_half_to_float(p >> 16));
}

// ---- R11G11B10F
uint gib_encode_ufloat(float f, uint mbits, bool rne) {
  uint u = floatBitsToUint(f);
  uint inf_bits = 31u << mbits;
  if ((u & 0x7fffffffu) > 0x7f800000u) return inf_bits | (1u << (mbits - 1u));  // NaN
  if ((u & 0x80000000u) != 0u) return 0u;  // negative, -0, -Inf
  if (u == 0x7f800000u) return inf_bits;   // +Inf
  return min(gib_round_to_small_float(u, mbits, rne), inf_bits - 1u);
}

float gib_decode_ufloat(uint bits, uint mbits) {
  uint e = bits >> mbits;
  uint m = bits & ((1u << mbits) - 1u);
  if (e == 31u) return uintBitsToFloat(0x7f800000u | (m << (23u - mbits)));  // Inf, NaN
  if (e == 0u) return float(m) * uintBitsToFloat((127u - 14u - mbits) << 23);  // m * 2^(-14-mbits)
  return uintBitsToFloat(((e + 112u) << 23) | (m << (23u - mbits)));
}

uint gib_pack_r11g11b10(vec3 rgb) {
  return gib_encode_ufloat(rgb.r, 6u, false) | (gib_encode_ufloat(rgb.g, 6u, false) << 11) |
         (gib_encode_ufloat(rgb.b, 5u, false) << 22);
}
uint gib_pack_r11g11b10_rne(vec3 rgb) {
  return gib_encode_ufloat(rgb.r, 6u, true) | (gib_encode_ufloat(rgb.g, 6u, true) << 11) |
         (gib_encode_ufloat(rgb.b, 5u, true) << 22);
}
vec3 gib_unpack_r11g11b10(uint p) {
  return vec3(gib_decode_ufloat(p & 0x7ffu, 6u), gib_decode_ufloat((p >> 11) & 0x7ffu, 6u),
              gib_decode_ufloat(p >> 22, 5u));
}

// ---- RGB9E5
uint gib_rgb9e5_clamp_bits(float f) {
  uint u = floatBitsToUint(f);
  return (u > 0x7f800000u) ? 0u : min(u, 0x477f8000u);  // NaN, negatives -> 0; max 65408
}

// floor(c / 2^unit_exp + 0.5) for the clamped channel with bits u.
uint gib_rgb9e5_round(uint u, int unit_exp) {
  if (u < 0x00800000u) return 0u;
  uint m = (u & 0x7fffffu) | 0x800000u;
  int shift = unit_exp - (int(u >> 23) - 150);
  if (shift > 24) return 0u;
  return (m + (1u << uint(shift - 1))) >> uint(shift);
}

uint gib_pack_rgb9e5(vec3 rgb) {
  uint r = gib_rgb9e5_clamp_bits(rgb.r);
  uint g = gib_rgb9e5_clamp_bits(rgb.g);
  uint b = gib_rgb9e5_clamp_bits(rgb.b);
  uint mx = max(r, max(g, b));
  int exp_shared = max(int(mx >> 23) - 127, -16) + 16;
  if (gib_rgb9e5_round(mx, exp_shared - 24) == 512u) exp_shared += 1;
  int unit = exp_shared - 24;
  return gib_rgb9e5_round(r, unit) | (gib_rgb9e5_round(g, unit) << 9) |
         (gib_rgb9e5_round(b, unit) << 18) | (uint(exp_shared) << 27);
}

// floor(c / 2^unit_exp + dither / 2^32) for the clamped channel with bits u: the stochastic
// rounding of gib_pack_rgb9e5_dither. A channel below 2^-7 units (shift > 31) gives 0.
uint gib_rgb9e5_round_dither(uint u, int unit_exp, uint dither) {
  if (u < 0x00800000u) return 0u;
  uint m = (u & 0x7fffffu) | 0x800000u;
  int shift = unit_exp - (int(u >> 23) - 150);
  if (shift > 31) return 0u;
  return (m + (dither >> uint(32 - shift))) >> uint(shift);
}

// RGB9E5 with stochastic rounding: each channel rounds up with probability equal to its
// fraction of a unit (dither uniform over uint), so the decoded value's expectation is the input
// (channels of at least 2^-7 units). For a store that blends with its own last value (a temporal
// filter): round-to-nearest there stops moving once a frame's change is below half a unit, so a
// slowly converging value sticks short of (or beyond) its limit; dithered, it keeps moving on
// average. The shared exponent is the smallest whose largest channel cannot round up to 512.
// CPU mirror: codecs::encode_rgb9e5_dither.
uint gib_pack_rgb9e5_dither(vec3 rgb, uint dither) {
  uint r = gib_rgb9e5_clamp_bits(rgb.r);
  uint g = gib_rgb9e5_clamp_bits(rgb.g);
  uint b = gib_rgb9e5_clamp_bits(rgb.b);
  uint mx = max(r, max(g, b));
  int exp_shared = max(int(mx >> 23) - 127, -16) + 16;
  if (gib_rgb9e5_round_dither(mx, exp_shared - 24, 0xffffffffu) == 512u) exp_shared += 1;
  int unit = exp_shared - 24;
  return gib_rgb9e5_round_dither(r, unit, dither) | (gib_rgb9e5_round_dither(g, unit, dither) << 9) |
         (gib_rgb9e5_round_dither(b, unit, dither) << 18) | (uint(exp_shared) << 27);
}

vec3 gib_unpack_rgb9e5(uint p) {
  float scale = uintBitsToFloat(((p >> 27) + 103u) << 23);  // 2^(e - 24): always a normal float
  return vec3(uvec3(p, p >> 9, p >> 18) & 0x1ffu) * scale;
}

#endif  // GIB_PACKING_GLSL
