// Codecs: the CPU mirrors in renderer/codecs/ against independent references (nearest-value
// search over every code of the format, the Vulkan spec's RGB9E5 formula in double), the GLSL in
// renderer/shaders/include/ against the CPU bit for bit (tests/codecs_test.comp, 2^20 values
// per codec spanning zero, float and format denormals, format maxima and beyond, negatives,
// NaN, Inf, rounding ties, random bit patterns), and both against the device's own format
// conversions (tests/codecs_format_test.comp: sampling E5B9G9R9 / B10G11R11 texels, an
// imageStore through a B10G11R11 storage image, vkCmdClearColorImage). Octahedral round trip
// and border mapping; SH2 projection and irradiance known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <vector>

#include "renderer/codecs/half.h"
#include "device_spec_shared.h"
#include "renderer/codecs/octahedral.h"
#include "renderer/codecs/r11g11b10.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/codecs/sh2.h"
#include "tests/codecs_test_shared.h"
#include "tests/gpu_fixture.h"
#include "tests/test_rng.h"

namespace gib {
namespace {

using namespace codecs;
using namespace codecs_test;

constexpr float kPi = std::numbers::pi_v<float>;

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float from_bits(uint32_t u) { return std::bit_cast<float>(u); }

using test::Rng;

// ---------------------------------------------------------------- references
// Every non-negative finite code of a small float format, decoded: the values ascend with the
// code, so the nearest representable value is found by binary search.
struct SmallFloatTable {
  std::vector<double> values;  // index = code
  explicit SmallFloatTable(uint32_t mbits) {
    for (uint32_t c = 0; c < (31u << mbits); ++c) {
      values.push_back(mbits == 10 ? double(half_to_float(uint16_t(c))) : double(ufloat_to_float(c, mbits)));
    }
  }
  // Code of the non-negative finite x: rne (ties to the even code) or toward zero; beyond the
  // largest value: `overflow` (the caller's policy).
  uint32_t round(double x, bool rne, uint32_t overflow_code) const {
    const uint32_t last = uint32_t(values.size() - 1);
    if (x >= values[last]) {
      if (x == values[last] || overflow_code == ~0u) return last;  // ~0u: saturate
      if (!rne) return overflow_code;
      // IEEE: round as if the exponent range went on; the value one step above the max (the
      // next power of two) has an even code, so the tie goes up, to the overflow code.
      const double next = 2 * values[last] - values[last - 1];
      return x >= (values[last] + next) / 2 ? overflow_code : last;
    }
    const auto it = std::upper_bound(values.begin(), values.end(), x);
    const uint32_t hi = uint32_t(it - values.begin()), lo = hi - 1;
    if (!rne) return lo;
    const double dlo = x - values[lo], dhi = values[hi] - x;
    if (dlo < dhi) return lo;
    if (dhi < dlo) return hi;
    return (lo & 1u) ? hi : lo;
  }
};

const SmallFloatTable& table(uint32_t mbits) {
  static const SmallFloatTable t10(10), t6(6), t5(5);
  return mbits == 10 ? t10 : (mbits == 6 ? t6 : t5);
}

uint16_t ref_half(float f, bool rne) {
  const uint32_t u = bits(f), sign = (u >> 16) & 0x8000u;
  if (std::isnan(f)) return uint16_t(sign | 0x7e00u | ((u >> 13) & 0x1ffu));
  if (std::isinf(f)) return uint16_t(sign | 0x7c00u);
  return uint16_t(sign | table(10).round(std::fabs(double(f)), rne, rne ? 0x7c00u : ~0u));
}

uint32_t ref_ufloat(float f, uint32_t mbits, bool rne) {
  if (std::isnan(f)) return (31u << mbits) | (1u << (mbits - 1));
  if (std::signbit(f)) return 0;
  if (std::isinf(f)) return 31u << mbits;
  return table(mbits).round(double(f), rne, ~0u);  // finite overflow: the max finite
}

uint32_t ref_r11g11b10(const float c[3], bool rne) {
  return ref_ufloat(c[0], 6, rne) | (ref_ufloat(c[1], 6, rne) << 11) | (ref_ufloat(c[2], 5, rne) << 22);
}

// The Vulkan spec's shared-exponent formula, in double (exact for float inputs).
uint32_t ref_rgb9e5(const float c[3]) {
  double v[3];
  for (int i = 0; i < 3; ++i) {
    const float x = c[i];
    v[i] = (std::isnan(x) || x <= 0.0f) ? 0.0 : std::min(double(x), 65408.0);
  }
  const double mx = std::max(v[0], std::max(v[1], v[2]));
  const int fl = mx > 0 ? std::max(std::ilogb(mx), -16) : -16;
  int e = fl + 16;
  if (std::floor(mx / std::ldexp(1.0, e - 24) + 0.5) == 512.0) ++e;
  uint32_t out = uint32_t(e) << 27;
  for (int i = 0; i < 3; ++i) out |= uint32_t(std::floor(v[i] / std::ldexp(1.0, e - 24) + 0.5)) << (9 * i);
  return out;
}

// ---------------------------------------------------------------- inputs
std::vector<float> special_floats() {
  std::vector<float> s = {
      0.0f, -0.0f, 1.0f, 0.5f, 1.0f / 3.0f, 2.0f, 3.0f, 100.0f, 1e-3f, 0.1f, -1.0f, -1e-8f,
      std::numeric_limits<float>::denorm_min(), from_bits(0x007fffffu), std::numeric_limits<float>::min(),
      -std::numeric_limits<float>::denorm_min(),
      std::ldexp(1.0f, -24), std::ldexp(1.0f, -25), std::ldexp(1.5f, -25), std::ldexp(1.0f, -26),
      std::ldexp(1.0f, -20), std::ldexp(1.0f, -21), std::ldexp(1.5f, -21), std::ldexp(1.0f, -19),
      std::ldexp(1.0f, -14), std::ldexp(1.0f, -15), std::ldexp(1.0f, -16), std::ldexp(1.0f, -17),
      std::ldexp(1.0f, -18), 6.1e-5f, 6.0e-8f,
      65504.0f, 65519.0f, 65520.0f, 65536.0f, 65024.0f, 65280.0f, 65279.0f, 65535.0f, 64512.0f,
      64768.0f, 65408.0f, 65472.0f, 65471.0f, 65473.0f, 1e5f, 1e10f, 1e30f,
      std::numeric_limits<float>::max(), -65504.0f, -1e30f,
      std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
      from_bits(0x7fc00000u), from_bits(0xffc00000u), from_bits(0x7f800001u), from_bits(0x7fffffffu),
      from_bits(0x7f802000u), from_bits(0xff812345u), from_bits(0x7fa00000u),
      // RGB9E5: the channel that scales to 0.5 - 2^-25 units (float "x + 0.5" would round up).
      std::ldexp(0.5f - std::ldexp(1.0f, -25), -8),
  };
  const size_t n = s.size();
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s[i])) continue;
    s.push_back(std::nextafter(s[i], std::numeric_limits<float>::infinity()));
    s.push_back(std::nextafter(s[i], -std::numeric_limits<float>::infinity()));
  }
  return s;
}

// A value on, at half a step past, or next to a rounding tie of a small float format.
float tie_value(Rng& rng, uint32_t mbits) {
  const auto& t = table(mbits).values;
  const uint32_t c = rng.below(uint32_t(t.size()));
  const double lo = t[c], step = c + 1 < t.size() ? t[c + 1] - t[c] : t[c] - t[c - 1];
  float v = float(lo + step / 2);  // exact: a few more bits than the format holds
  switch (rng.below(4)) {
    case 0: return float(lo);
    case 1: return v;
    case 2: return std::nextafter(v, 0.0f);
    default: return std::nextafter(v, std::numeric_limits<float>::infinity());
  }
}

float random_float(Rng& rng, const std::vector<float>& specials) {
  switch (rng.below(10)) {
    case 0: case 1: return from_bits(rng.next());  // any bit pattern
    case 2: case 3: case 4: {  // positive, exponent uniform over the formats' range and beyond
      const int e = int(rng.below(46)) - 28;  // 2^-28 .. 2^17
      return from_bits((uint32_t(e + 127) << 23) | (rng.next() & 0x7fffffu));
    }
    case 5: return specials[rng.below(uint32_t(specials.size()))];
    case 6: return tie_value(rng, 10);
    case 7: return tie_value(rng, 6);
    case 8: return tie_value(rng, 5);
    default: return rng.uniform() * 4.0f;
  }
}

// RGB9E5 element ties: channels at k + 0.5 units of the max's shared exponent, and maxima that
// round up to 512 units (the exponent correction).
void rgb9e5_tie(Rng& rng, float c[3]) {
  const int e = int(rng.below(31));
  const float unit = std::ldexp(1.0f, e - 24);
  c[0] = float(256 + rng.below(256)) * unit;
  if (rng.below(4) == 0) c[0] = std::nextafter(511.5f * unit, rng.below(2) ? 0.0f : 1e30f);
  if (rng.below(4) == 0) c[0] = 511.5f * unit;
  for (int i = 1; i < 3; ++i) {
    float v = (float(rng.below(512)) + 0.5f) * unit;
    if (rng.below(3) == 0) v = std::nextafter(v, rng.below(2) ? 0.0f : 1e30f);
    c[i] = v;
  }
  std::swap(c[0], c[rng.below(3)]);
}

std::vector<CodecsTestIn> make_inputs(uint32_t count, uint64_t seed) {
  Rng rng(seed);
  const std::vector<float> specials = special_floats();
  std::vector<CodecsTestIn> in(count);
  for (uint32_t i = 0; i < count; ++i) {
    float c[4];
    for (float& v : c) v = random_float(rng, specials);
    if (rng.below(8) == 0) rgb9e5_tie(rng, c);
    in[i] = {bits(c[0]), bits(c[1]), bits(c[2]), bits(c[3])};
    // Every pair of half codes appears in z, every 11-bit code in y (as words to decode).
    if (i < 65536) in[i].z = i | ((65535u - i) << 16);
    if (i < 4096) in[i].y = (i & 0x7ffu) * 0x00200801u;  // same code in all three channels
  }
  // All pairs of specials in the first two channels.
  uint32_t k = 70000;
  for (float a : specials)
    for (float b : specials) {
      if (k >= count) break;
      const float c = specials[k % specials.size()];
      in[k] = {bits(a), bits(b), bits(c), bits(b)};
      ++k;
    }
  return in;
}

// ---------------------------------------------------------------- CPU tests
TEST(CodecsCpu, HalfMatchesNearestValueReference) {
  // Every 509th float bit pattern (8.4 million floats) plus the tie cases.
  uint64_t checked = 0, bad_rne = 0, bad_rtz = 0;
  for (uint64_t u = 0; u <= 0xffffffffull; u += 509) {
    const float f = from_bits(uint32_t(u));
    if (float_to_half(f) != ref_half(f, true)) ++bad_rne;
    if (float_to_half_rtz(f) != ref_half(f, false)) ++bad_rtz;
    ++checked;
  }
  Rng rng(1);
  for (int i = 0; i < 1000000; ++i) {
    const float f = rng.below(2) ? tie_value(rng, 10) : -tie_value(rng, 10);
    if (float_to_half(f) != ref_half(f, true)) ++bad_rne;
    if (float_to_half_rtz(f) != ref_half(f, false)) ++bad_rtz;
    ++checked;
  }
  std::printf("[codecs] half vs nearest-value reference: %llu floats, %llu RNE / %llu RTZ mismatches\n",
              (unsigned long long)checked, (unsigned long long)bad_rne, (unsigned long long)bad_rtz);
  EXPECT_EQ(bad_rne, 0u);
  EXPECT_EQ(bad_rtz, 0u);
  // Round trip of every half code; NaNs come back quiet with their payload.
  for (uint32_t h = 0; h < 65536; ++h) {
    const bool nan = (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu);
    ASSERT_EQ(float_to_half(half_to_float(uint16_t(h))), nan ? (h | 0x200u) : h) << h;
  }
  EXPECT_EQ(float_to_half(65519.996f), 0x7bffu);
  EXPECT_EQ(float_to_half(65520.0f), 0x7c00u);
  EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25)), 0u);              // tie to even (0)
  EXPECT_EQ(float_to_half(std::ldexp(1.5f, -24)), 2u);              // tie to even (2)
  EXPECT_EQ(float_to_half(std::nextafter(std::ldexp(1.0f, -25), 1.0f)), 1u);
}

TEST(CodecsCpu, R11G11B10MatchesNearestValueReference) {
  uint64_t checked = 0, bad = 0;
  for (uint32_t mbits : {6u, 5u}) {
    for (uint64_t u = 0; u <= 0xffffffffull; u += 509) {
      const float f = from_bits(uint32_t(u));
      bad += encode_ufloat_rtz(f, mbits) != ref_ufloat(f, mbits, false);
      bad += encode_ufloat_rne(f, mbits) != ref_ufloat(f, mbits, true);
      ++checked;
    }
    Rng rng(2 + mbits);
    for (int i = 0; i < 1000000; ++i) {
      const float f = tie_value(rng, mbits);
      bad += encode_ufloat_rtz(f, mbits) != ref_ufloat(f, mbits, false);
      bad += encode_ufloat_rne(f, mbits) != ref_ufloat(f, mbits, true);
      ++checked;
    }
    for (uint32_t c = 0; c < (32u << mbits); ++c) {  // every code round trips (NaN: canonical)
      const float f = ufloat_to_float(c, mbits);
      const bool nan = (c >> mbits) == 31 && (c & ((1u << mbits) - 1));
      const uint32_t expect = nan ? (31u << mbits) | (1u << (mbits - 1)) : c;  // one NaN code
      ASSERT_EQ(encode_ufloat_rtz(f, mbits), expect) << c;
      ASSERT_EQ(encode_ufloat_rne(f, mbits), expect) << c;
    }
  }
  Rng rng(12);
  const std::vector<float> specials = special_floats();
  for (int i = 0; i < 1000000; ++i) {
    const float c[3] = {random_float(rng, specials), random_float(rng, specials), random_float(rng, specials)};
    bad += encode_r11g11b10(c) != ref_r11g11b10(c, false);
    bad += encode_r11g11b10_rne(c) != ref_r11g11b10(c, true);
    ++checked;
  }
  std::printf("[codecs] r11g11b10 channels vs nearest-value reference: %llu floats, %llu mismatches\n",
              (unsigned long long)checked, (unsigned long long)bad);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(encode_r11g11b10(1e9f, 1e9f, 1e9f), 0xf7fdffbfu);  // max finite, never Inf
  EXPECT_EQ(encode_r11g11b10(-1.0f, -0.0f, -std::numeric_limits<float>::infinity()), 0u);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(encode_r11g11b10(inf, nan, -nan), 0x7c0u | (0x7e0u << 11) | (0x3f0u << 22));
}

TEST(CodecsCpu, Rgb9e5MatchesSpecFormula) {
  Rng rng(3);
  const std::vector<float> specials = special_floats();
  uint64_t bad = 0, n = 0;
  double worst_rel = 0;  // error relative to the shared exponent's unit, must be <= 0.5
  for (int i = 0; i < 2000000; ++i) {
    float c[3] = {random_float(rng, specials), random_float(rng, specials), random_float(rng, specials)};
    if (i % 4 == 0) rgb9e5_tie(rng, c);
    const uint32_t p = encode_rgb9e5(c);
    bad += p != ref_rgb9e5(c);
    ++n;
    float d[3];
    decode_rgb9e5(p, d);
    const double unit = std::ldexp(1.0, int(p >> 27) - 24);
    for (int k = 0; k < 3; ++k) {
      const double clamped = (std::isnan(c[k]) || c[k] <= 0) ? 0.0 : std::min(double(c[k]), 65408.0);
      worst_rel = std::max(worst_rel, std::fabs(double(d[k]) - clamped) / unit);
    }
  }
  std::printf("[codecs] rgb9e5 vs spec formula: %llu triples, %llu mismatches, max error %.4f units\n",
              (unsigned long long)n, (unsigned long long)bad, worst_rel);
  EXPECT_EQ(bad, 0u);
  EXPECT_LE(worst_rel, 0.5);
  EXPECT_EQ(encode_rgb9e5(65408.0f, 1e30f, std::numeric_limits<float>::infinity()), 0xffffffffu);
  EXPECT_EQ(encode_rgb9e5(-1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f), 0u);
  float d[3];
  decode_rgb9e5(encode_rgb9e5(1.0f, 0.5f, 0.25f), d);
  EXPECT_EQ(d[0], 1.0f);
  EXPECT_EQ(d[1], 0.5f);
  EXPECT_EQ(d[2], 0.25f);
}

// Stochastic rounding (encode_rgb9e5_dither): each channel decodes to the floor or the ceiling of
// its value in units of the shared exponent, and over dither values spread evenly across the
// 32-bit range the mean decoded value is the input (what keeps a temporal filter's store
// unbiased). Known answers: half-way dither equals round-half-up whenever the exponents agree.
TEST(CodecsCpu, Rgb9e5DitherIsUnbiased) {
  Rng rng(11);
  constexpr int kDithers = 4096;
  double worst_bias = 0, worst_step = 0;
  uint64_t same_as_nearest = 0, comparable = 0;
  for (int i = 0; i < 3000; ++i) {
    // Values over 12 octaves around 1, channels within 2^-6 of the largest (>= 2^-7 units).
    float c[3];
    const float scale = std::ldexp(1.0f, int(rng.below(12)) - 6);
    for (float& v : c) v = scale * (0.02f + 0.98f * rng.uniform());
    const uint32_t exp_dither = encode_rgb9e5_dither(c, 0) >> 27;
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < kDithers; ++k) {
      const uint32_t dither = uint32_t((uint64_t(k) << 32) / kDithers) + rng.below(1u << 20);
      const uint32_t p = encode_rgb9e5_dither(c, dither);
      ASSERT_EQ(p >> 27, exp_dither) << "the shared exponent does not depend on the dither";
      const double unit = std::ldexp(1.0, int(p >> 27) - 24);
      float d[3];
      decode_rgb9e5(p, d);
      for (int j = 0; j < 3; ++j) {
        sum[j] += d[j];
        worst_step = std::max(worst_step, std::fabs(double(d[j]) - c[j]) / unit);  // < 1 unit
      }
    }
    const double unit = std::ldexp(1.0, int(exp_dither) - 24);
    for (int j = 0; j < 3; ++j) worst_bias = std::max(worst_bias, std::fabs(sum[j] / kDithers - c[j]) / unit);
    const uint32_t nearest = encode_rgb9e5(c);
    if (nearest >> 27 == exp_dither) {
      ++comparable;
      same_as_nearest += encode_rgb9e5_dither(c, 0x80000000u) == nearest;
    }
  }
  std::printf("[codecs] rgb9e5 stochastic rounding: mean error %.2e units over %d dithers, largest step %.4f units; "
              "half-way dither = round-half-up in %llu of %llu\n", worst_bias, kDithers, worst_step,
              (unsigned long long)same_as_nearest, (unsigned long long)comparable);
  EXPECT_LT(worst_bias, 2.0 / kDithers);  // stratified dithers: the mean is exact up to the strata
  EXPECT_LT(worst_step, 1.0);
  EXPECT_EQ(same_as_nearest, comparable);
  EXPECT_GT(comparable, 2500u);
  // Clamping as encode_rgb9e5: NaN and negatives give 0, the maximum stays 65408.
  EXPECT_EQ(encode_rgb9e5_dither(std::array<float, 3>{-1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f}.data(),
                                 0xffffffffu),
            0u);
  float d[3];
  decode_rgb9e5(encode_rgb9e5_dither(std::array<float, 3>{65408.0f, 1e30f, 1.0f}.data(), 0xffffffffu), d);
  EXPECT_EQ(d[0], 65408.0f);
  EXPECT_EQ(d[1], 65408.0f);
}

// Angle in degrees between two unit vectors (stable for small angles).
double angle_deg(Vec3 a, Vec3 b) {
  const Vec3 c = cross(a, b);
  return std::atan2(double(length(c)), double(dot(a, b))) * 180.0 / std::numbers::pi;
}

Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 v{rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1};
    const float l = dot(v, v);
    if (l > 1e-4f && l <= 1.0f) return v / std::sqrt(l);
  }
}

TEST(CodecsCpu, OctahedralRoundTrip) {
  Rng rng(4);
  double worst = 0, worst_uv = 0, worst_q16 = 0;
  for (int i = 0; i < 1000000; ++i) {
    Vec3 n = random_unit(rng);
    if (i < 6) n = Vec3{i == 0 ? 1.f : i == 1 ? -1.f : 0.f, i == 2 ? 1.f : i == 3 ? -1.f : 0.f, i == 4 ? 1.f : i == 5 ? -1.f : 0.f};
    const Vec2 uv = oct_encode(n);
    ASSERT_TRUE(uv.x >= 0 && uv.x <= 1 && uv.y >= 0 && uv.y <= 1);
    worst = std::max(worst, angle_deg(n, oct_decode(uv)));
    // 16-bit unorm per coordinate (e.g. RG16 storage).
    const Vec2 q{std::round(uv.x * 65535.0f) / 65535.0f, std::round(uv.y * 65535.0f) / 65535.0f};
    worst_q16 = std::max(worst_q16, angle_deg(n, oct_decode(q)));
    const Vec2 uv2{rng.uniform(), rng.uniform()};
    const Vec2 back = oct_encode(oct_decode(uv2));
    // Points of the outer edges and their mirror images are the same direction.
    const bool edge = uv2.x == 0 || uv2.y == 0;
    if (!edge) worst_uv = std::max(worst_uv, double(std::max(std::fabs(back.x - uv2.x), std::fabs(back.y - uv2.y))));
  }
  std::printf("[codecs] octahedral: float round trip max %.3g deg, uv round trip max %.3g, RG16 unorm max %.3g deg\n",
              worst, worst_uv, worst_q16);
  EXPECT_LT(worst, 1e-4);
  EXPECT_LT(worst_uv, 4e-7);
  EXPECT_LT(worst_q16, 0.004);
  // Landmarks.
  EXPECT_NEAR(oct_encode({0, 0, 1}).x, 0.5f, 0);
  EXPECT_NEAR(oct_encode({0, 0, -1}).x, 1.0f, 0);
  EXPECT_NEAR(oct_encode({1, 0, 0}).x, 1.0f, 0);
  EXPECT_NEAR(oct_encode({1, 0, 0}).y, 0.5f, 0);
}

// Value of a border texel must come from the interior texel continuing the map across the edge:
// its direction is as close to the direction of the border texel's interior neighbour as two
// adjacent interior texels can be, and a bilinear lookup across the edge stays accurate.
TEST(CodecsCpu, OctahedralBorderMapping) {
  for (int n : {4, 6, 8, 16}) {
    // Largest angle between 8-connected interior neighbours.
    double spacing = 0;
    for (int y = 1; y <= n; ++y)
      for (int x = 1; x <= n; ++x)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (x + dx < 1 || x + dx > n || y + dy < 1 || y + dy > n) continue;
            spacing = std::max(spacing, angle_deg(oct_texel_direction({x, y}, n),
                                                  oct_texel_direction({x + dx, y + dy}, n)));
          }
    double worst = 0;
    int border = 0;
    for (int y = 0; y <= n + 1; ++y)
      for (int x = 0; x <= n + 1; ++x) {
        const Texel t{x, y};
        const Texel s = oct_border_source(t, n);
        const bool interior = x >= 1 && x <= n && y >= 1 && y <= n;
        if (interior) {
          ASSERT_EQ(s, t);
          continue;
        }
        ++border;
        ASSERT_TRUE(s.x >= 1 && s.x <= n && s.y >= 1 && s.y <= n);
        const Texel a{std::clamp(x, 1, n), std::clamp(y, 1, n)};  // adjacent interior texel
        worst = std::max(worst, angle_deg(oct_texel_direction(s, n), oct_texel_direction(a, n)));
      }
    EXPECT_EQ(border, 4 * n + 4);
    EXPECT_LE(worst, spacing * 1.0001) << n;
    std::printf("[codecs] octahedral %dx%d border: max angle source vs neighbour %.2f deg (interior spacing %.2f)\n",
                n, n, worst, spacing);
  }
  // The gluing the border encodes: each outer edge of the square is one great semicircle
  // traversed twice, direction(0, v) == direction(0, 1 - v) (and likewise for the other edges).
  double glue = 0;
  for (int i = 0; i <= 1000; ++i) {
    const float v = float(i) / 1000.0f;
    glue = std::max({glue, angle_deg(oct_decode({0, v}), oct_decode({0, 1 - v})),
                     angle_deg(oct_decode({1, v}), oct_decode({1, 1 - v})),
                     angle_deg(oct_decode({v, 0}), oct_decode({1 - v, 0})),
                     angle_deg(oct_decode({v, 1}), oct_decode({1 - v, 1}))});
  }
  EXPECT_LT(glue, 1e-4);
  // All four corners are -z.
  for (Vec2 c : {Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}, Vec2{1, 1}}) EXPECT_LT(angle_deg(oct_decode(c), {0, 0, -1}), 1e-4);
  // Spelled out for 8x8: left border row 2 copies (1, 7); top border column 1 copies (8, 1);
  // corners copy the opposite corners.
  EXPECT_EQ(oct_border_source({0, 2}, 8), (Texel{1, 7}));
  EXPECT_EQ(oct_border_source({9, 2}, 8), (Texel{8, 7}));
  EXPECT_EQ(oct_border_source({1, 0}, 8), (Texel{8, 1}));
  EXPECT_EQ(oct_border_source({3, 9}, 8), (Texel{6, 8}));
  EXPECT_EQ(oct_border_source({0, 0}, 8), (Texel{8, 8}));
  EXPECT_EQ(oct_border_source({9, 0}, 8), (Texel{1, 8}));
  EXPECT_EQ(oct_border_source({0, 9}, 8), (Texel{8, 1}));
  EXPECT_EQ(oct_border_source({9, 9}, 8), (Texel{1, 1}));
  EXPECT_EQ(oct_border_source({4, 5}, 8), (Texel{4, 5}));

  // Bilinear reconstruction of a smooth function of direction from a bordered 8x8 tile: the
  // error at directions whose taps straddle the tile edge is no worse than inside.
  const int n = 8, w = n + 2;
  auto f = [](Vec3 d) { return 1.0f + 0.5f * d.x - 0.3f * d.y + 0.7f * d.z; };
  std::vector<float> tile(w * w), naive(w * w);
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      const Texel s = oct_border_source({x, y}, n);
      tile[y * w + x] = f(oct_texel_direction(s, n));
      naive[y * w + x] = f(oct_texel_direction({std::clamp(x, 1, n), std::clamp(y, 1, n)}, n));
    }
  auto sample = [&](const std::vector<float>& t, Vec3 d) {
    const Vec2 c = oct_tile_coord(d, n);
    const float fx = c.x - 0.5f, fy = c.y - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float ax = fx - float(x0), ay = fy - float(y0);
    auto at = [&](int x, int y) { return t[std::clamp(y, 0, w - 1) * w + std::clamp(x, 0, w - 1)]; };
    return (at(x0, y0) * (1 - ax) + at(x0 + 1, y0) * ax) * (1 - ay) +
           (at(x0, y0 + 1) * (1 - ax) + at(x0 + 1, y0 + 1) * ax) * ay;
  };
  Rng rng(5);
  double inner = 0, edge = 0, edge_naive = 0, edge_sq = 0, edge_naive_sq = 0;
  int edge_count = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 d = random_unit(rng);
    const Vec2 c = oct_tile_coord(d, n);
    const bool near_edge = c.x < 1.5f || c.x > n + 0.5f || c.y < 1.5f || c.y > n + 0.5f;
    const double e = std::fabs(sample(tile, d) - f(d));
    if (near_edge) {
      const double en = std::fabs(sample(naive, d) - f(d));
      edge = std::max(edge, e);
      edge_naive = std::max(edge_naive, en);
      edge_sq += e * e;
      edge_naive_sq += en * en;
      ++edge_count;
    } else {
      inner = std::max(inner, e);
    }
  }
  const double edge_rms = std::sqrt(edge_sq / edge_count), naive_rms = std::sqrt(edge_naive_sq / edge_count);
  std::printf("[codecs] octahedral 8x8 bilinear of a linear function: max error inner %.4f, edge %.4f (rms %.4f); "
              "clamp-to-edge border: edge max %.4f (rms %.4f)\n", inner, edge, edge_rms, edge_naive, naive_rms);
  EXPECT_LE(edge, inner * 1.5);
  // Negative control: a clamp-to-edge border is clearly worse across the edges.
  EXPECT_GT(edge_naive, edge * 1.4);
  EXPECT_GT(naive_rms, edge_rms * 1.2);
}

// Spherical Fibonacci directions (uniform, 4 pi / count solid angle each).
Vec3 fibonacci(uint32_t i, uint32_t count) {
  const double golden = (std::sqrt(5.0) - 1) / 2;
  const double z = 1 - (2 * double(i) + 1) / double(count);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = 2 * std::numbers::pi * std::fmod(double(i) * golden, 1.0);
  return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
}

Vec4 project(uint32_t count, auto radiance) {
  double c[4] = {};
  for (uint32_t i = 0; i < count; ++i) {
    const Vec3 d = fibonacci(i, count);
    const Vec4 p = sh2_project(d, radiance(d));
    c[0] += p.x; c[1] += p.y; c[2] += p.z; c[3] += p.w;
  }
  const double w = 4 * std::numbers::pi / count;
  return {float(c[0] * w), float(c[1] * w), float(c[2] * w), float(c[3] * w)};
}

TEST(CodecsCpu, Sh2KnownAnswers) {
  EXPECT_NEAR(sh2_basis({0, 1, 0}).y, kShY1, 0);
  EXPECT_NEAR(sh2_basis({0, 0, 1}).z, kShY1, 0);
  EXPECT_NEAR(sh2_basis({1, 0, 0}).w, kShY1, 0);
  constexpr uint32_t kCount = 200000;
  Rng rng(6);
  // Constant radiance L: irradiance pi L, so irradiance / pi = L in every direction.
  const Vec4 c = project(kCount, [](Vec3) { return 2.5f; });
  double worst_const = 0;
  for (int i = 0; i < 10000; ++i) worst_const = std::max(worst_const, std::fabs(sh2_irradiance(c, random_unit(rng)) - 2.5));
  // Linear radiance a + b.w lies in the first two bands: irradiance / pi = a + (2/3) b.n exactly.
  const Vec3 b{0.3f, -0.2f, 0.5f};
  const Vec4 cl = project(kCount, [&](Vec3 d) { return 1.0f + dot(b, d); });
  double worst_lin = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = random_unit(rng);
    worst_lin = std::max(worst_lin, std::fabs(sh2_irradiance(cl, n) - (1.0 + 2.0 / 3.0 * dot(b, n))));
  }
  // Uniform upper hemisphere (sky) of radiance L: irradiance / pi = L (1 + cos) / 2, which two
  // bands hold exactly.
  const Vec4 ch = project(kCount, [](Vec3 d) { return d.z > 0 ? 1.0f : 0.0f; });
  double worst_sky = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = random_unit(rng);
    worst_sky = std::max(worst_sky, std::fabs(sh2_irradiance(ch, n) - (1.0 + n.z) / 2));
  }
  // Directional light of irradiance E0 (at normal incidence) from l: coefficients E0 Y(l);
  // two bands give E0/pi (1/4 + cos/2) against the true E0/pi max(0, cos): the error is at most
  // E0/(4 pi), reached at cos = 1 (0.75 vs 1), 0 (0.25 vs 0) and -1 (-0.25 vs 0).
  const Vec3 l = normalize(Vec3{0.2f, 0.5f, 0.8f});
  const float e0 = 3.0f;
  const Vec4 b_l = sh2_basis(l);
  const Vec4 cd{e0 * b_l.x, e0 * b_l.y, e0 * b_l.z, e0 * b_l.w};
  double worst_dir = 0, at_zenith = 0;
  for (int i = 0; i < 100000; ++i) {
    const Vec3 n = i == 0 ? l : random_unit(rng);
    const double truth = e0 * std::max(0.0f, dot(n, l)) / kPi;
    const double err = std::fabs(sh2_irradiance(cd, n) - truth);
    worst_dir = std::max(worst_dir, err);
    if (i == 0) at_zenith = err;
  }
  const double bound = e0 / (4 * kPi);
  std::printf("[codecs] SH2 irradiance/pi: constant %.2e, linear %.2e, sky hemisphere %.2e (abs, %u-point "
              "projection); directional max error %.5f vs bound E0/(4pi) = %.5f (at the light %.5f)\n",
              worst_const, worst_lin, worst_sky, kCount, worst_dir, bound, at_zenith);
  EXPECT_LT(worst_const, 1e-4);
  EXPECT_LT(worst_lin, 1e-4);
  EXPECT_LT(worst_sky, 2e-3);  // the step at the horizon limits the quadrature, not the SH
  EXPECT_LE(worst_dir, bound * (1 + 1e-5));
  EXPECT_NEAR(at_zenith, bound, bound * 1e-5);
}

// ---------------------------------------------------------------- GPU tests
class CodecsGpu : public test::GpuTest {
 protected:
  std::shared_ptr<Buffer> buffer(const void* data, uint64_t bytes, const char* name) {
    auto b = gpu().create_buffer(bytes, BufferUsage::storage, name);
    if (data) gpu().upload(*b, data, bytes);
    return b;
  }
  template <class Out, class In>
  std::vector<Out> run_codecs(const std::vector<In>& in, uint32_t mode, uint32_t count,
                              std::vector<SpecConstant> spec_constants = {}) {
    auto in_buf = buffer(in.data(), in.size() * sizeof(In), "codecs_test.in");
    auto out_buf = buffer(nullptr, uint64_t(count) * sizeof(Out), "codecs_test.out");
    ComputePipelineDesc desc{"codecs_test.comp",
                             {{CODECS_TEST_BINDING_IN, DescriptorKind::storage_buffer},
                              {CODECS_TEST_BINDING_OUT, DescriptorKind::storage_buffer}},
                             sizeof(CodecsTestPush), std::move(spec_constants)};
    auto pipeline = gpu().compute_pipeline(desc);
    const Bind binds[] = {{CODECS_TEST_BINDING_IN, in_buf.get()}, {CODECS_TEST_BINDING_OUT, out_buf.get()}};
    const CodecsTestPush push{count, mode};
    auto cmd = gpu().begin();
    cmd->bind(*pipeline, binds, &push, sizeof(push));
    cmd->dispatch((count + CODECS_TEST_WORKGROUP_SIZE - 1) / CODECS_TEST_WORKGROUP_SIZE);
    gpu().submit(std::move(cmd));
    std::vector<Out> out(count);
    gpu().download(*out_buf, out.data(), out.size() * sizeof(Out));
    return out;
  }
};

// gib_float_to_half has two forms: the device's packHalf2x16 as is (devices whose rounding probe
// says nearest even: the test above runs it there) and packHalf2x16 corrected to nearest even
// (every other device). The corrected form, forced here, gives the CPU mirror's bits too.
TEST_F(CodecsGpu, CorrectedHalfPathMatchesCpuBitForBit) {
  constexpr uint32_t kCount = 1u << 20;
  const std::vector<CodecsTestIn> in = make_inputs(kCount, 11);
  const std::vector<CodecsTestOut> out =
      run_codecs<CodecsTestOut>(in, CODECS_TEST_MODE_PACKING, kCount, {{glsl::kGibSpecNativeHalfRne, 0u}});
  uint64_t bad = 0;
  for (uint32_t i = 0; i < kCount; ++i) {
    const float f[4] = {from_bits(in[i].x), from_bits(in[i].y), from_bits(in[i].z), from_bits(in[i].w)};
    bad += out[i].half_xy != pack_half2x16(f[0], f[1]);
    bad += out[i].half_zw != pack_half2x16(f[2], f[3]);
  }
  EXPECT_EQ(bad, 0u) << "of " << 2 * kCount << " packed pairs";
}

TEST_F(CodecsGpu, PackingMatchesCpuBitForBit) {
  constexpr uint32_t kCount = 1u << 20;
  const std::vector<CodecsTestIn> in = make_inputs(kCount, 7);
  const std::vector<CodecsTestOut> out = run_codecs<CodecsTestOut>(in, CODECS_TEST_MODE_PACKING, kCount);
  uint64_t bad_e5 = 0, bad_e5_dither = 0, bad_r11 = 0, bad_r11_rne = 0, bad_half = 0, bad_e5_dec = 0, bad_r11_dec = 0,
           bad_half_dec = 0, native_rne = 0, native_rtz = 0, native_neither = 0, bad_half_rtz = 0;
  int reported = 0;
  uint64_t native_nan = 0, native_nan_same = 0, native_nan_is_nan = 0;
  uint64_t nan_in = 0, inf_in = 0, neg_in = 0, denorm_in = 0, above_max_in = 0;
  for (uint32_t i = 0; i < kCount; ++i) {
    const CodecsTestIn& w = in[i];
    const CodecsTestOut& o = out[i];
    const float f[4] = {from_bits(w.x), from_bits(w.y), from_bits(w.z), from_bits(w.w)};
    for (float v : f) {
      nan_in += std::isnan(v);
      inf_in += std::isinf(v);
      neg_in += std::signbit(v) && !std::isnan(v);
      denorm_in += std::fabs(v) > 0 && std::fabs(v) < std::ldexp(1.0f, -14);
      above_max_in += std::fabs(v) > 65024.0f && std::isfinite(v);
    }
    bad_e5 += o.rgb9e5 != encode_rgb9e5(f);
    bad_e5_dither += o.rgb9e5_dither != encode_rgb9e5_dither(f, w.w);
    bad_r11 += o.r11g11b10 != encode_r11g11b10(f);
    bad_r11_rne += o.r11g11b10_rne != encode_r11g11b10_rne(f);
    bad_half += o.half_xy != pack_half2x16(f[0], f[1]);
    bad_half += o.half_zw != pack_half2x16(f[2], f[3]);
    for (int k = 0; k < 4; ++k) {
      const uint32_t native = (k < 2 ? o.native_half_xy : o.native_half_zw) >> (16 * (k & 1)) & 0xffffu;
      if (std::isnan(f[k])) {  // no rounding to classify: does the device keep our NaN bits?
        const uint32_t rtz = (k < 2 ? o.half_rtz_xy : o.half_rtz_zw) >> (16 * (k & 1)) & 0xffffu;
        bad_half_rtz += (rtz & 0x7c00u) != 0x7c00u || (rtz & 0x3ffu) == 0;
        native_nan_same += native == float_to_half(f[k]);
        native_nan_is_nan += (native & 0x7c00u) == 0x7c00u && (native & 0x3ffu);
        ++native_nan;
        continue;
      }
      // gib_pack_half2x16_rtz: toward zero bit for bit (NaN: a NaN, the device's payload).
      const uint32_t rtz = (k < 2 ? o.half_rtz_xy : o.half_rtz_zw) >> (16 * (k & 1)) & 0xffffu;
      bad_half_rtz += rtz != float_to_half_rtz(f[k]);
      if (native == float_to_half(f[k])) ++native_rne;
      if (native == float_to_half_rtz(f[k])) ++native_rtz;
      if (native != float_to_half(f[k]) && native != float_to_half_rtz(f[k])) ++native_neither;
    }
    float d[3];
    decode_rgb9e5(w.x, d);
    bad_e5_dec += bits(d[0]) != bits(o.e5_r) || bits(d[1]) != bits(o.e5_g) || bits(d[2]) != bits(o.e5_b);
    decode_r11g11b10(w.y, d);
    bad_r11_dec += bits(d[0]) != bits(o.r11_r) || bits(d[1]) != bits(o.r11_g) || bits(d[2]) != bits(o.r11_b);
    float h[2];
    unpack_half2x16(w.z, h);
    bad_half_dec += bits(h[0]) != bits(o.half_lo) || bits(h[1]) != bits(o.half_hi);
    const bool any = o.rgb9e5 != encode_rgb9e5(f) || o.r11g11b10 != encode_r11g11b10(f) ||
                     o.r11g11b10_rne != encode_r11g11b10_rne(f) || o.half_xy != pack_half2x16(f[0], f[1]) ||
                     o.half_zw != pack_half2x16(f[2], f[3]);
    if (any && ++reported <= 3)
      ADD_FAILURE() << "mismatch at " << i << std::hex << ": float bits " << w.x << " " << w.y << " " << w.z << " "
                    << w.w << "; gpu rgb9e5 " << o.rgb9e5 << " cpu " << encode_rgb9e5(f) << ", gpu r11 " << o.r11g11b10
                    << " cpu " << encode_r11g11b10(f) << ", gpu half " << o.half_xy << " " << o.half_zw << " cpu "
                    << pack_half2x16(f[0], f[1]) << " " << pack_half2x16(f[2], f[3]);
  }
  std::printf("[codecs] %s: %u elements (%llu NaN, %llu Inf, %llu negative, %llu below 2^-14, %llu finite above 65024 "
              "among the %u floats)\n", gpu().info().name.c_str(), kCount, (unsigned long long)nan_in,
              (unsigned long long)inf_in, (unsigned long long)neg_in, (unsigned long long)denorm_in,
              (unsigned long long)above_max_in, 4 * kCount);
  std::printf("[codecs] GPU vs CPU mismatches: rgb9e5 %llu, r11g11b10 %llu, r11g11b10_rne %llu, half %llu (of %u), "
              "decode rgb9e5 %llu, r11g11b10 %llu, half %llu\n", (unsigned long long)bad_e5, (unsigned long long)bad_r11,
              (unsigned long long)bad_r11_rne, (unsigned long long)bad_half, 2 * kCount, (unsigned long long)bad_e5_dec,
              (unsigned long long)bad_r11_dec, (unsigned long long)bad_half_dec);
  std::printf("[codecs] GPU vs CPU mismatches: rgb9e5 with stochastic rounding %llu (of %u), half toward zero %llu "
              "(of %u)\n", (unsigned long long)bad_e5_dither, kCount, (unsigned long long)bad_half_rtz, 4 * kCount);
  std::printf("[codecs] device packHalf2x16 (non-NaN floats): equals RNE %llu, equals RTZ %llu, neither %llu; NaN "
              "floats %llu: same bits %llu, a NaN %llu\n", (unsigned long long)native_rne, (unsigned long long)native_rtz,
              (unsigned long long)native_neither, (unsigned long long)native_nan, (unsigned long long)native_nan_same,
              (unsigned long long)native_nan_is_nan);
  EXPECT_EQ(bad_e5, 0u);
  EXPECT_EQ(bad_e5_dither, 0u);
  EXPECT_EQ(bad_r11, 0u);
  EXPECT_EQ(bad_r11_rne, 0u);
  EXPECT_EQ(bad_half, 0u);
  EXPECT_EQ(bad_e5_dec, 0u);
  EXPECT_EQ(bad_r11_dec, 0u);
  EXPECT_EQ(bad_half_dec, 0u);
  EXPECT_EQ(bad_half_rtz, 0u);
}

TEST_F(CodecsGpu, DeviceFormatConversionsMatchCpu) {
  constexpr uint32_t kW = 1024, kH = 1024, kCount = kW * kH;
  const std::vector<CodecsTestIn> in = make_inputs(kCount, 8);
  Rng rng(9);
  std::vector<uint32_t> e5_bits(kCount), b10_bits(kCount);
  std::vector<float> store_in(4 * size_t(kCount));
  for (uint32_t i = 0; i < kCount; ++i) {
    const float f[3] = {from_bits(in[i].x), from_bits(in[i].y), from_bits(in[i].z)};
    // Half the texels hold encodes of the test floats, half random words (every word is a
    // valid E5B9G9R9 texel; B10G11R11 words cover denormals, Inf and NaN codes).
    e5_bits[i] = (i & 1) ? rng.next() : encode_rgb9e5(f);
    b10_bits[i] = (i & 1) ? rng.next() : encode_r11g11b10(f);
    for (int k = 0; k < 3; ++k) store_in[4 * size_t(i) + k] = f[k];
    store_in[4 * size_t(i) + 3] = 1.0f;
  }
  auto e5 = gpu().create_image(Format::e5b9g9r9_float, kW, kH, "codecs_test.e5");
  auto b10 = gpu().create_image(Format::b10g11r11_float, kW, kH, "codecs_test.b10");
  auto store = gpu().create_image(Format::b10g11r11_float, kW, kH, "codecs_test.b10_store");
  auto store16 = gpu().create_image(Format::rgba16_float, kW, kH, "codecs_test.rgba16f_store");
  gpu().upload(*e5, e5_bits.data(), e5_bits.size() * 4);
  gpu().upload(*b10, b10_bits.data(), b10_bits.size() * 4);
  auto store_buf = buffer(store_in.data(), store_in.size() * 4, "codecs_test.store_in");
  auto out_buf = buffer(nullptr, uint64_t(kCount) * sizeof(CodecsFormatOut), "codecs_test.format_out");
  ComputePipelineDesc desc{"codecs_format_test.comp",
                           {{CODECS_FORMAT_BINDING_E5, DescriptorKind::sampled_image},
                            {CODECS_FORMAT_BINDING_B10, DescriptorKind::sampled_image},
                            {CODECS_FORMAT_BINDING_STORE, DescriptorKind::storage_image},
                            {CODECS_FORMAT_BINDING_STORE_IN, DescriptorKind::storage_buffer},
                            {CODECS_FORMAT_BINDING_OUT, DescriptorKind::storage_buffer},
                            {CODECS_FORMAT_BINDING_STORE16, DescriptorKind::storage_image}},
                           sizeof(CodecsFormatPush)};
  auto pipeline = gpu().compute_pipeline(desc);
  Bind binds[6] = {};
  binds[0].binding = CODECS_FORMAT_BINDING_E5;
  binds[0].image = e5.get();
  binds[1].binding = CODECS_FORMAT_BINDING_B10;
  binds[1].image = b10.get();
  binds[2].binding = CODECS_FORMAT_BINDING_STORE;
  binds[2].image = store.get();
  binds[3].binding = CODECS_FORMAT_BINDING_STORE_IN;
  binds[3].buffer = store_buf.get();
  binds[4].binding = CODECS_FORMAT_BINDING_OUT;
  binds[4].buffer = out_buf.get();
  binds[5].binding = CODECS_FORMAT_BINDING_STORE16;
  binds[5].image = store16.get();
  const CodecsFormatPush push{kW, kH};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch(kW / CODECS_FORMAT_WORKGROUP, kH / CODECS_FORMAT_WORKGROUP);
  gpu().submit(std::move(cmd));
  std::vector<CodecsFormatOut> out(kCount);
  gpu().download(*out_buf, out.data(), out.size() * sizeof(CodecsFormatOut));
  const std::vector<uint8_t> stored = gpu().download(*store);
  ASSERT_EQ(stored.size(), size_t(kCount) * 4);
  // imageStore to R16G16B16A16_SFLOAT: Vulkan lets a device round toward zero or to nearest.
  // gi_denoise rounds its horizontal result toward zero itself (gib_pack_half2x16_rtz), which is
  // what lavapipe's store does: this says which one a device does.
  const std::vector<uint8_t> stored16 = gpu().download(*store16);
  ASSERT_EQ(stored16.size(), size_t(kCount) * 8);
  uint64_t half_channels = 0, half_rtz = 0, half_rne = 0, half_neither = 0, half_nan = 0, half_nan_ok = 0;
  for (uint32_t i = 0; i < kCount; ++i)
    for (int k = 0; k < 3; ++k) {
      uint16_t h;
      std::memcpy(&h, stored16.data() + 8 * size_t(i) + 2 * k, 2);
      const float f = store_in[4 * size_t(i) + k];
      if (std::isnan(f)) {
        ++half_nan;
        half_nan_ok += (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu);
        continue;
      }
      ++half_channels;
      half_rtz += h == float_to_half_rtz(f);
      half_rne += h == float_to_half(f);
      half_neither += h != float_to_half_rtz(f) && h != float_to_half(f);
    }
  std::printf("[codecs] imageStore R16G16B16A16_SFLOAT: non-NaN channels %llu: equal to toward zero %llu, to nearest "
              "even %llu, neither %llu; NaN channels %llu: stored a NaN %llu\n", (unsigned long long)half_channels,
              (unsigned long long)half_rtz, (unsigned long long)half_rne, (unsigned long long)half_neither,
              (unsigned long long)half_nan, (unsigned long long)half_nan_ok);
  EXPECT_EQ(half_neither, 0u);
  EXPECT_EQ(half_nan_ok, half_nan);
  if (gpu().info().is_software()) {
    EXPECT_EQ(half_rtz, half_channels) << "lavapipe's RGBA16F store rounds toward zero (gi_denoise relies on it for "
                                          "unchanged lavapipe goldens)";
  }

  uint64_t e5_bad = 0, b10_bad = 0, b10_bad_nan_only = 0, store_rtz = 0, store_rne = 0, store_bad = 0;
  uint64_t store_nan = 0, store_nan_ok = 0, store_nan_same = 0, store_finite_bad = 0;
  uint64_t store_channel_rtz = 0, store_channel_rne = 0, store_channel_neither = 0, first_store_bad = ~0ull;
  for (uint32_t i = 0; i < kCount; ++i) {
    float d[3];
    decode_rgb9e5(e5_bits[i], d);
    const CodecsFormatOut& o = out[i];
    e5_bad += bits(d[0]) != bits(o.e5_r) || bits(d[1]) != bits(o.e5_g) || bits(d[2]) != bits(o.e5_b);
    decode_r11g11b10(b10_bits[i], d);
    const float g[3] = {o.b10_r, o.b10_g, o.b10_b};
    bool exact = true, same = true;
    for (int k = 0; k < 3; ++k) {
      exact &= bits(d[k]) == bits(g[k]);
      same &= bits(d[k]) == bits(g[k]) || (std::isnan(d[k]) && std::isnan(g[k]));
    }
    b10_bad += !same;
    b10_bad_nan_only += same && !exact;
    uint32_t s;
    std::memcpy(&s, stored.data() + 4 * size_t(i), 4);
    const float* f = &store_in[4 * size_t(i)];
    const uint32_t rtz = encode_r11g11b10(f), rne = encode_r11g11b10_rne(f);
    store_rtz += s == rtz;
    store_rne += s == rne;
    store_bad += s != rtz;
    const int shifts[3] = {0, 11, 22};
    const uint32_t masks[3] = {0x7ffu, 0x7ffu, 0x3ffu};
    for (int k = 0; k < 3; ++k) {
      const uint32_t sc = (s >> shifts[k]) & masks[k], tc = (rtz >> shifts[k]) & masks[k], nc = (rne >> shifts[k]) & masks[k];
      if (std::isnan(f[k])) {  // NaN: the device must store a NaN; its bits are its own
        const uint32_t mb = k == 2 ? 5 : 6;
        store_nan_ok += (sc >> mb) == 31 && (sc & ((1u << mb) - 1));
        store_nan_same += sc == tc;
        ++store_nan;
        continue;
      }
      if (sc != tc && ++store_finite_bad == 1) first_store_bad = i;
      if (tc == nc) continue;  // the float is exact in the format: no rounding to tell
      store_channel_rtz += sc == tc;
      store_channel_rne += sc == nc;
      store_channel_neither += sc != tc && sc != nc;
    }
  }
  std::printf("[codecs] %s device formats, %u texels: sampled E5B9G9R9 vs CPU decode %llu mismatches; sampled "
              "B10G11R11 %llu mismatches (+%llu differing only in NaN bits)\n", gpu().info().name.c_str(), kCount,
              (unsigned long long)e5_bad, (unsigned long long)b10_bad, (unsigned long long)b10_bad_nan_only);
  std::printf("[codecs] imageStore B10G11R11: texels equal to the CPU encode (toward zero) %llu, to RNE %llu, of %u; "
              "non-NaN channels differing %llu; inexact channels: toward zero %llu, nearest even %llu, neither %llu; "
              "NaN channels %llu: stored a NaN %llu, our NaN bits %llu\n", (unsigned long long)store_rtz,
              (unsigned long long)store_rne, kCount, (unsigned long long)store_finite_bad,
              (unsigned long long)store_channel_rtz, (unsigned long long)store_channel_rne,
              (unsigned long long)store_channel_neither, (unsigned long long)store_nan, (unsigned long long)store_nan_ok,
              (unsigned long long)store_nan_same);
  EXPECT_EQ(e5_bad, 0u);
  EXPECT_EQ(b10_bad, 0u);
  if (first_store_bad != ~0ull) {
    const float* f = &store_in[4 * first_store_bad];
    uint32_t s;
    std::memcpy(&s, stored.data() + 4 * first_store_bad, 4);
    ADD_FAILURE() << "first store mismatch at " << first_store_bad << std::hex << ": floats " << bits(f[0]) << " "
                  << bits(f[1]) << " " << bits(f[2]) << " stored " << s << " cpu " << encode_r11g11b10(f);
  }
  // Every non-NaN channel is the CPU encode (toward zero: lavapipe and NVIDIA H200 both store
  // that way); a NaN stays a NaN, with exactly our bits on lavapipe (NVIDIA sets all mantissa bits).
  EXPECT_EQ(store_finite_bad, 0u);
  EXPECT_EQ(store_nan_ok, store_nan);
  if (gpu().info().is_software()) {
    EXPECT_EQ(store_bad, 0u);
  }
}

// vkCmdClearColorImage converts floats to the image format in the driver: the device's own
// RGB9E5 encoder (shaders cannot store E5B9G9R9). Lavapipe's equals ours (the spec's round half
// up) bit for bit; NVIDIA's clear truncates mantissas (a few values one unit lower), so on other
// devices this only reports. The B10G11R11 clear is reported, not asserted: lavapipe's clear
// flushes values below 2^-14 to 0 (its shader stores keep denormals), NVIDIA's NaN bits differ.
TEST_F(CodecsGpu, DeviceClearEncodesMatchCpu) {
  const std::vector<float> s = special_floats();
  auto e5 = gpu().create_image(Format::e5b9g9r9_float, 1, 1, "codecs_test.e5_clear");
  auto b10 = gpu().create_image(Format::b10g11r11_float, 1, 1, "codecs_test.b10_clear");
  Rng rng(10);
  int e5_bad = 0, b10_rtz = 0, b10_rne = 0, b10_other = 0, n = 0;
  for (int i = 0; i < int(s.size()) + 100; ++i) {
    float c[4] = {s[rng.below(uint32_t(s.size()))], s[rng.below(uint32_t(s.size()))], s[rng.below(uint32_t(s.size()))], 1.0f};
    if (i < int(s.size())) c[0] = c[1] = c[2] = s[i];
    if (i % 5 == 4) rgb9e5_tie(rng, c);
    if (i == 0) {  // the channel at 0.5 - 2^-25 units: half up in exact arithmetic gives 0
      c[0] = 1.0f;
      c[1] = std::ldexp(0.5f - std::ldexp(1.0f, -25), -8);
      c[2] = 0.0f;
    }
    auto cmd = gpu().begin();
    cmd->clear(*e5, c);
    cmd->clear(*b10, c);
    gpu().submit(std::move(cmd));
    uint32_t pe, pb;
    std::memcpy(&pe, gpu().download(*e5).data(), 4);
    std::memcpy(&pb, gpu().download(*b10).data(), 4);
    if (pe != encode_rgb9e5(c)) {
      ++e5_bad;
      if (e5_bad <= 8)
        std::printf("[codecs] clear E5B9G9R9 (%a %a %a): device %08x cpu %08x\n", c[0], c[1], c[2], pe, encode_rgb9e5(c));
    }
    b10_rtz += pb == encode_r11g11b10(c);
    b10_rne += pb == encode_r11g11b10_rne(c);
    if (pb != encode_r11g11b10(c) && pb != encode_r11g11b10_rne(c) && ++b10_other <= 8)
      std::printf("[codecs] clear B10G11R11 (%a %a %a): device %08x, toward zero %08x, nearest even %08x\n", c[0],
                  c[1], c[2], pb, encode_r11g11b10(c), encode_r11g11b10_rne(c));
    ++n;
  }
  std::printf("[codecs] clears: E5B9G9R9 %d of %d differ from the CPU encode; B10G11R11 equals toward-zero %d, "
              "nearest-even %d, neither %d\n", e5_bad, n, b10_rtz, b10_rne, b10_other);
  if (gpu().info().is_software()) {
    EXPECT_EQ(e5_bad, 0);
  }
}

TEST_F(CodecsGpu, GeometryMatchesCpu) {
  constexpr uint32_t kCount = 1u << 18;
  Rng rng(11);
  std::vector<CodecsGeomIn> in(kCount);
  for (uint32_t i = 0; i < kCount; ++i) {
    const Vec3 d = random_unit(rng);
    const int interior = 4 + 2 * int(rng.below(7));
    in[i] = {d.x, d.y, d.z, rng.uniform(), rng.uniform(), int(rng.below(interior + 2)), int(rng.below(interior + 2)), interior};
    if (i < 64) in[i].u = (i & 1) ? 0.0f : 1.0f;  // edges
  }
  const std::vector<CodecsGeomOut> out = run_codecs<CodecsGeomOut>(in, CODECS_TEST_MODE_GEOMETRY, kCount);
  double worst_uv = 0, worst_dir = 0, worst_irr = 0, worst_basis = 0;
  int border_bad = 0;
  for (uint32_t i = 0; i < kCount; ++i) {
    const CodecsGeomIn& g = in[i];
    const CodecsGeomOut& o = out[i];
    const Vec3 d = normalize(Vec3{g.dx, g.dy, g.dz});
    const Vec2 uv = oct_encode(d);
    worst_uv = std::max(worst_uv, double(std::max(std::fabs(uv.x - o.u), std::fabs(uv.y - o.v))));
    worst_dir = std::max(worst_dir, angle_deg(oct_decode({g.u, g.v}), normalize(Vec3{o.nx, o.ny, o.nz})));
    const Vec4 sh{g.u, g.v, g.dx, g.dy};
    worst_irr = std::max(worst_irr, double(std::fabs(sh2_irradiance(sh, d) - o.irradiance)));
    const Vec4 b = sh2_basis(d);
    worst_basis = std::max({worst_basis, double(std::fabs(b.x - o.b0)), double(std::fabs(b.y - o.b1)),
                            double(std::fabs(b.z - o.b2)), double(std::fabs(b.w - o.b3))});
    border_bad += !(oct_border_source({g.tx, g.ty}, g.interior) == Texel{o.sx, o.sy});
  }
  std::printf("[codecs] GPU vs CPU geometry (%u): oct encode max |duv| %.3g, decode max %.3g deg, SH irradiance "
              "max %.3g, basis max %.3g, border mapping mismatches %d\n", kCount, worst_uv, worst_dir, worst_irr,
              worst_basis, border_bad);
  EXPECT_LT(worst_uv, 1e-6);
  EXPECT_LT(worst_dir, 1e-4);
  EXPECT_LT(worst_irr, 1e-5);
  EXPECT_LT(worst_basis, 1e-6);
  EXPECT_EQ(border_bad, 0);
}

}  // namespace
}  // namespace gib
