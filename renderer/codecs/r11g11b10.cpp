#include "renderer/codecs/r11g11b10.h"

#include <bit>

#include "renderer/codecs/half.h"

namespace gib::codecs {

namespace {
uint32_t encode_ufloat(float f, uint32_t mbits, bool rne) {
  const uint32_t u = std::bit_cast<uint32_t>(f);
  const uint32_t inf = 31u << mbits;
  if ((u & 0x7fffffffu) > 0x7f800000u) return inf | (1u << (mbits - 1));  // NaN (any sign)
  if (u & 0x80000000u) return 0;                                          // negative, -0, -Inf
  if (u == 0x7f800000u) return inf;                                       // +Inf
  const uint32_t bits = round_to_small_float(u, mbits, rne);
  return bits >= inf ? inf - 1u : bits;  // finite stays finite: clamp to the max
}
}  // namespace

uint32_t encode_ufloat_rtz(float f, uint32_t mbits) { return encode_ufloat(f, mbits, false); }
uint32_t encode_ufloat_rne(float f, uint32_t mbits) { return encode_ufloat(f, mbits, true); }

uint32_t encode_r11g11b10(const float rgb[3]) {
  return encode_ufloat_rtz(rgb[0], 6) | (encode_ufloat_rtz(rgb[1], 6) << 11) |
         (encode_ufloat_rtz(rgb[2], 5) << 22);
}

uint32_t encode_r11g11b10_rne(const float rgb[3]) {
  return encode_ufloat_rne(rgb[0], 6) | (encode_ufloat_rne(rgb[1], 6) << 11) |
         (encode_ufloat_rne(rgb[2], 5) << 22);
}

}  // namespace gib::codecs
