#include "renderer/codecs/ycocg_sh.h"

#include <bit>
#include <cmath>

namespace gib::codecs {
namespace {

constexpr int kMinExponent = -100, kMaxExponent = 127;

bool finite_bits(float v) { return (std::bit_cast<uint32_t>(v) & 0x7f800000u) != 0x7f800000u; }

// Smallest e with 2^e >= m, for a finite m >= 2^-100 (normal).
int magnitude_exponent(float m) {
  const uint32_t b = std::bit_cast<uint32_t>(m);
  int e = int((b >> 23) & 255u) - 127;  // m = 1.f x 2^e
  if ((b & 0x7fffffu) != 0) ++e;
  return e;
}

uint32_t quantise(float scaled, bool is_unsigned) {
  // One correctly rounded multiply, one correctly rounded add, then floor: as the GLSL (precise).
  if (is_unsigned) {
    volatile float x = std::fmin(std::fmax(scaled, 0.0f), 1.0f) * 255.0f;
    return uint32_t(std::floor(x + 0.5f));
  }
  volatile float x = std::fmin(std::fmax(scaled, -1.0f), 1.0f) * 127.0f;
  return uint32_t(int32_t(std::floor(x + 0.5f)) + 127);
}

}  // namespace

std::array<uint32_t, 2> pack_ycocg_sh(const YcocgSh& in) {
  YcocgSh v = in;
  float m = 0.0f;
  for (float& x : v) {
    if (!finite_bits(x)) x = 0.0f;
    m = std::fmax(m, std::fabs(x));
  }
  v[0] = std::fmax(v[0], 0.0f);
  if (m < 0x1p-100f) return {127u << 8 | 127u << 16 | 127u << 24, 127u | 127u << 8 | uint32_t(kMinExponent + 128) << 16};
  int e = magnitude_exponent(m);
  if (e > kMaxExponent) e = kMaxExponent;
  std::array<uint32_t, 6> q;
  for (int i = 0; i < 6; ++i) q[i] = quantise(std::ldexp(v[i], -e), i == 0);
  return {q[0] | q[1] << 8 | q[2] << 16 | q[3] << 24, q[4] | q[5] << 8 | uint32_t(e + 128) << 16};
}

YcocgSh unpack_ycocg_sh(const std::array<uint32_t, 2>& w) {
  const int e = int((w[1] >> 16) & 0xffffu) - 128;
  const uint32_t q[6] = {w[0] & 255u, (w[0] >> 8) & 255u, (w[0] >> 16) & 255u, w[0] >> 24, w[1] & 255u, (w[1] >> 8) & 255u};
  YcocgSh v;
  v[0] = std::ldexp(float(q[0]) * (1.0f / 255.0f), e);
  for (int i = 1; i < 6; ++i) v[i] = std::ldexp(float(int32_t(q[i]) - 127) * (1.0f / 127.0f), e);
  return v;
}

std::array<float, 3> rgb_to_ycocg(float r, float g, float b) {
  return {0.25f * r + 0.5f * g + 0.25f * b, 0.5f * r - 0.5f * b, -0.25f * r + 0.5f * g - 0.25f * b};
}
std::array<float, 3> ycocg_to_rgb(float y, float co, float cg) { return {y + co - cg, y + cg, y - co - cg}; }

}  // namespace gib::codecs
