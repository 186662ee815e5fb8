// Image textures on the GPU (tests/textures_test.comp) against the CPU mirror
// (renderer/scene/texture.h): the bilinear filter at a given level, the footprint's level and
// the sample at it, bit for bit, for sRGB and linear textures of power-of-two and odd sizes,
// uvs well outside [0, 1) (wrapping), texel centres and edges, and footprints around every
// level boundary.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <vector>

#include "renderer/scene/texture.h"
#include "tests/gpu_fixture.h"
#include "tests/test_rng.h"
#include "tests/textures_test_shared.h"

namespace gib {
namespace {

using namespace textures_test;

using test::Rng;

Texture random_texture(uint32_t w, uint32_t h, bool srgb, Rng& rng) {
  std::vector<uint8_t> px(size_t(w) * h * 4);
  for (uint8_t& c : px) c = uint8_t(rng.next());
  return make_texture("random", w, h, px.data(), srgb);
}

class TexturesGpu : public test::GpuTest {
 protected:
  std::shared_ptr<Buffer> buffer(const void* data, uint64_t bytes, const char* name) {
    auto b = gpu().create_buffer(bytes, BufferUsage::storage, name);
    if (data) gpu().upload(*b, data, bytes);
    return b;
  }
  std::vector<TexturesTestOut> run(const std::vector<uint32_t>& words, const std::vector<TexturesTestQuery>& q) {
    auto tex = buffer(words.data(), words.size() * 4, "textures_test.textures");
    auto in = buffer(q.data(), q.size() * sizeof(TexturesTestQuery), "textures_test.queries");
    auto out = buffer(nullptr, q.size() * sizeof(TexturesTestOut), "textures_test.out");
    ComputePipelineDesc desc{"textures_test.comp",
                             {{TEXTURES_TEST_BINDING_TEXTURES, DescriptorKind::storage_buffer},
                              {TEXTURES_TEST_BINDING_QUERIES, DescriptorKind::storage_buffer},
                              {TEXTURES_TEST_BINDING_OUT, DescriptorKind::storage_buffer}},
                             sizeof(TexturesTestPush)};
    auto pipeline = gpu().compute_pipeline(desc);
    const Bind binds[] = {{TEXTURES_TEST_BINDING_TEXTURES, tex.get()},
                          {TEXTURES_TEST_BINDING_QUERIES, in.get()},
                          {TEXTURES_TEST_BINDING_OUT, out.get()}};
    const TexturesTestPush push{uint32_t(q.size())};
    auto cmd = gpu().begin();
    cmd->bind(*pipeline, binds, &push, sizeof(push));
    cmd->dispatch((uint32_t(q.size()) + TEXTURES_TEST_WORKGROUP_SIZE - 1) / TEXTURES_TEST_WORKGROUP_SIZE);
    gpu().submit(std::move(cmd));
    std::vector<TexturesTestOut> o(q.size());
    gpu().download(*out, o.data(), o.size() * sizeof(TexturesTestOut));
    return o;
  }
};

TEST_F(TexturesGpu, FetchFilterAndLevelMatchCpuBitForBit) {
  Rng rng(18);
  const std::vector<Texture> textures = {random_texture(16, 16, true, rng), random_texture(13, 7, false, rng),
                                         random_texture(1, 5, true, rng), random_texture(64, 32, false, rng)};
  const std::vector<uint32_t> words = pack_textures(textures);
  std::vector<TexturesTestQuery> q;
  for (uint32_t i = 0; i < 16384; ++i) {
    TexturesTestQuery x{};
    x.texture = i % uint32_t(textures.size());
    x.level = (i / 4) % 8;  // past the chain's end too (clamped)
    const Texture& t = textures[x.texture];
    const uint32_t w = std::max(1u, t.width >> std::min<uint32_t>(x.level, uint32_t(t.mips.size() - 1)));
    switch (i % 3) {
      case 0:  // anywhere, wrapping
        x.u = rng.uniform(-3, 3);
        x.v = rng.uniform(-3, 3);
        break;
      case 1:  // texel centres and edges of the level
        x.u = float(rng.next() % (2 * w)) / float(2 * w);
        x.v = float(rng.next() % 64) / 64.0f;
        break;
      default:  // tiny and exact values
        x.u = float(int(rng.next() % 5) - 2) * 0.5f;
        x.v = std::ldexp(1.0f, -int(rng.next() % 30));
    }
    // Footprints from 1/8 texel to 2^7 texels, half of them on exact powers of two (level ties).
    const float texels = (i % 2) ? std::ldexp(1.0f, int(rng.next() % 11) - 3) * std::sqrt(2.0f)
                                 : std::ldexp(rng.uniform(1, 2), int(rng.next() % 11) - 3);
    const float angle = rng.uniform(0, 6.2831853f);
    x.dudx = texels * std::cos(angle) / float(t.width);
    x.dvdx = texels * std::sin(angle) / float(t.height);
    x.dudy = -x.dvdx * rng.uniform(0, 1);
    x.dvdy = x.dudx * rng.uniform(0, 1);
    q.push_back(x);
  }
  const std::vector<TexturesTestOut> out = run(words, q);
  size_t bad_bilinear = 0, bad_level = 0, bad_sample = 0;
  int reported = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const TexturesTestQuery& x = q[i];
    const Vec4 b = texture_bilinear(words, x.texture, x.level, {x.u, x.v});
    const uint32_t level = texture_level(words, x.texture, {x.dudx, x.dvdx}, {x.dudy, x.dvdy});
    const Vec4 s = texture_bilinear(words, x.texture, level, {x.u, x.v});
    const float bf[4] = {b.x, b.y, b.z, b.w}, sf[4] = {s.x, s.y, s.z, s.w};
    bool bb = false, sb = false;
    for (int k = 0; k < 4; ++k) {
      bb |= out[i].bilinear[k] != std::bit_cast<uint32_t>(bf[k]);
      sb |= out[i].sampled[k] != std::bit_cast<uint32_t>(sf[k]);
    }
    bad_bilinear += bb;
    bad_sample += sb;
    bad_level += out[i].level != level;
    if ((bb || sb || out[i].level != level) && reported++ < 5)
      ADD_FAILURE() << "query " << i << " texture " << x.texture << " level " << x.level << " uv (" << x.u << ", " << x.v
                    << "): bilinear r cpu " << b.x << " gpu " << std::bit_cast<float>(out[i].bilinear[0])
                    << "; footprint level cpu " << level << " gpu " << out[i].level;
  }
  std::printf("[textures] %zu queries over %zu textures (%zu words): bilinear %zu, level %zu, sample %zu differ\n",
              q.size(), textures.size(), words.size(), bad_bilinear, bad_level, bad_sample);
  EXPECT_EQ(bad_bilinear, 0u);
  EXPECT_EQ(bad_level, 0u);
  EXPECT_EQ(bad_sample, 0u);
}

}  // namespace
}  // namespace gib
