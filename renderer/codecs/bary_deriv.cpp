#include "renderer/codecs/bary_deriv.h"

#include <algorithm>
#include <cmath>

#include "renderer/codecs/half.h"

namespace gib::codecs {

uint16_t pack_bary_deriv(float d, bool flag) {
  if (std::isnan(d)) d = 0.0f;
  d = std::clamp(d, -kBaryDerivMax, kBaryDerivMax);
  const uint16_t h = float_to_half(d);
  return uint16_t(h | (flag ? kBaryDerivFlagBit : 0u));
}

float unpack_bary_deriv(uint16_t packed) { return half_to_float(uint16_t(packed & ~kBaryDerivFlagBit)); }

bool bary_deriv_flag(uint16_t packed) { return (packed & kBaryDerivFlagBit) != 0; }

float unit_z_from_xy(float x, float y, bool negative) {
  const float xy = x * x + y * y;
  const float z = std::sqrt(std::max(0.0f, 1.0f - xy));
  return negative ? -z : z;
}

}  // namespace gib::codecs
