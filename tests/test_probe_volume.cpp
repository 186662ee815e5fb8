// The probe-volume technique (renderer/techniques/probe_volume/): its YCoCg SH codec on the CPU
// and the GPU, known answers of the codec, and the octahedral tile borders its probes use.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "renderer/codecs/octahedral.h"
#include "renderer/codecs/ycocg_sh.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using namespace codecs;

TEST(YcocgSh, KnownAnswers) {
  // Largest value 1: magnitude 2^0; Y0 1 -> 255, -1 -> 0 (biased snorm), 0.5 -> 191 (63.5 rounds up).
  auto w = pack_ycocg_sh({1.0f, -1.0f, 0.5f, 0.0f, 0.25f, -0.25f});
  EXPECT_EQ(w[0], 255u | 0u << 8 | 191u << 16 | 127u << 24);
  EXPECT_EQ(w[1], 159u | 95u << 8 | 128u << 16);  // 0.25 x 127 = 31.75 -> 32; -31.75 -> -32 (floor(-31.25))
  YcocgSh v = unpack_ycocg_sh(w);
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[1], -1.0f);
  EXPECT_NEAR(v[2], 0.5f, 0.5f / 127.0f);
  EXPECT_EQ(v[3], 0.0f);
  // Magnitude 3 -> 2^2: 3 / 4 x 255 = 191.25 -> 191.
  w = pack_ycocg_sh({3.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f});
  EXPECT_EQ(w[0] & 255u, 191u);
  EXPECT_EQ(w[1] >> 16, 130u);
  EXPECT_NEAR(unpack_ycocg_sh(w)[0], 3.0f, 4.0f / 255.0f);
  // Non-finite values encode as 0, a negative Y0 clamps to 0, all-zero input decodes to zeros.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  v = unpack_ycocg_sh(pack_ycocg_sh({nan, inf, -inf, 2.0f, 0.0f, 0.0f}));
  EXPECT_EQ(v[0], 0.0f);
  EXPECT_EQ(v[1], 0.0f);
  EXPECT_EQ(v[2], 0.0f);
  EXPECT_EQ(v[3], 2.0f);
  v = unpack_ycocg_sh(pack_ycocg_sh({-1.0f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f}));
  EXPECT_EQ(v[0], 0.0f);
  for (float x : unpack_ycocg_sh(pack_ycocg_sh({0, 0, 0, 0, 0, 0}))) EXPECT_EQ(x, 0.0f);
  // YCoCg round trip.
  auto ycocg = rgb_to_ycocg(0.8f, 0.5f, 0.2f);
  auto rgb = ycocg_to_rgb(ycocg[0], ycocg[1], ycocg[2]);
  EXPECT_FLOAT_EQ(rgb[0], 0.8f);
  EXPECT_FLOAT_EQ(rgb[1], 0.5f);
  EXPECT_FLOAT_EQ(rgb[2], 0.2f);
}

TEST(YcocgSh, ErrorWithinOneStepOfTheMagnitude) {
  // Every value comes back within half a quantisation step of 2^e (the power-of-two magnitude):
  // 2^e / 510 for Y0, 2^e / 254 for the signed values.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-20.0f, 20.0f);
  for (int i = 0; i < 20000; ++i) {
    const float s = std::exp2(scale(rng));
    YcocgSh in{std::fabs(u(rng)) * s, u(rng) * s, u(rng) * s, u(rng) * s, u(rng) * s, u(rng) * s};
    auto w = pack_ycocg_sh(in);
    const float m = std::ldexp(1.0f, int((w[1] >> 16) & 0xffffu) - 128);
    YcocgSh out = unpack_ycocg_sh(w);
    for (int k = 0; k < 6; ++k) {
      ASSERT_LE(std::fabs(in[k]), m) << i;
      ASSERT_LE(std::fabs(out[k] - in[k]), m * (k == 0 ? 1.0f / 510.0f : 1.0f / 254.0f) * 1.0001f) << i << " " << k;
    }
  }
}

TEST(ProbeTiles, BorderTexelsCopyTheirOctahedralNeighbour) {
  // The probe tiles' borders (irradiance 5x5 + 1, radiance / visibility 10x10 + 1): every edge
  // and corner texel copies an interior texel, and that texel's direction is the border
  // texel's own (its centre mapped back onto the octahedron) to within one texel, so bilinear
  // filtering across the tile edge blends neighbouring directions.
  for (int n : {5, 10}) {
    const float texel_angle = 3.2f / float(n);  // generous: an octahedral texel spans < pi / n
    for (int y = 0; y < n + 2; ++y)
      for (int x = 0; x < n + 2; ++x) {
        const Texel t{x, y};
        const Texel s = oct_border_source(t, n);
        const bool border = x == 0 || y == 0 || x == n + 1 || y == n + 1;
        if (!border) {
          EXPECT_EQ(s.x, x);
          EXPECT_EQ(s.y, y);
          continue;
        }
        ASSERT_GE(s.x, 1);
        ASSERT_LE(s.x, n);
        ASSERT_GE(s.y, 1);
        ASSERT_LE(s.y, n);
        // Direction of the border texel's centre, wrapped onto the octahedron by reflection.
        float u = (float(x) - 0.5f) / float(n), v = (float(y) - 0.5f) / float(n);
        if (u < 0.0f || u > 1.0f) { u = u < 0.0f ? -u : 2.0f - u; v = 1.0f - v; }
        if (v < 0.0f || v > 1.0f) { v = v < 0.0f ? -v : 2.0f - v; u = 1.0f - u; }
        const Vec3 a = oct_decode(Vec2{u, v});
        const Vec3 b = oct_decode(Vec2{(float(s.x) - 0.5f) / float(n), (float(s.y) - 0.5f) / float(n)});
        const float c = std::fmin(1.0f, a.x * b.x + a.y * b.y + a.z * b.z);
        EXPECT_LT(std::acos(c), texel_angle) << "n " << n << " border texel " << x << "," << y;
      }
  }
}

class ProbeVolumeGpu : public test::GpuTest {};

TEST_F(ProbeVolumeGpu, YcocgShMatchesCpuBitForBit) {
  constexpr uint32_t kCount = 4096;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-40.0f, 40.0f);
  std::vector<uint32_t> in(6 * kCount);
  const float specials[] = {0.0f, -0.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(), 1e-38f, 3.4e38f, 0.5f, 1.0f, 1.0f + 0x1p-23f};
  for (uint32_t i = 0; i < kCount; ++i) {
    const float s = std::exp2(scale(rng));
    for (uint32_t k = 0; k < 6; ++k) {
      float v = u(rng) * s;
      if (i < 64) v = specials[(i + k * 3) % std::size(specials)];
      in[6 * i + k] = std::bit_cast<uint32_t>(v);
    }
  }
  auto in_buf = gpu().create_buffer(in.size() * 4, BufferUsage::storage, "ycocg_sh_test.in");
  auto out_buf = gpu().create_buffer(uint64_t(kCount) * 32, BufferUsage::storage, "ycocg_sh_test.out");
  gpu().upload(*in_buf, in.data(), in.size() * 4);
  auto pipeline = gpu().compute_pipeline(
      {"ycocg_sh_test.comp", {{0, DescriptorKind::storage_buffer}, {1, DescriptorKind::storage_buffer}}, 4});
  const Bind binds[] = {{0, in_buf.get()}, {1, out_buf.get()}};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &kCount, 4);
  cmd->dispatch(kCount / 64);
  gpu().submit(std::move(cmd));
  std::vector<uint32_t> out(8 * kCount);
  gpu().download(*out_buf, out.data(), out.size() * 4);
  for (uint32_t i = 0; i < kCount; ++i) {
    YcocgSh v;
    for (uint32_t k = 0; k < 6; ++k) v[k] = std::bit_cast<float>(in[6 * i + k]);
    const auto w = pack_ycocg_sh(v);
    ASSERT_EQ(out[8 * i], w[0]) << "entry " << i;
    ASSERT_EQ(out[8 * i + 1], w[1]) << "entry " << i;
    const YcocgSh d = unpack_ycocg_sh(w);
    for (uint32_t k = 0; k < 6; ++k) ASSERT_EQ(out[8 * i + 2 + k], std::bit_cast<uint32_t>(d[k])) << i << " " << k;
  }
}

}  // namespace
}  // namespace gib
