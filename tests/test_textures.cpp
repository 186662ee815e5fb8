// Image textures, on the CPU: decode and mip-chain known answers, sRGB vs
// linear decoding and filtering, bilinear and level-selection known answers, the glTF import
// of a textured MASK material (features, alpha kinds, bytes), its alpha mask in the BVH (a ray
// through a transparent texel misses) and baked average opacity, an export round trip that keeps
// the texels, and bad images (undecodable, too large) as one line naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/scene/bvh.h"
#include "renderer/scene/gltf_export.h"
#include "renderer/scene/gltf_import.h"
#include "renderer/scene/material_eval.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/scene/texture.h"
#include "tests/temp_dir.h"
#include "tests/texture_test_content.h"

namespace gib {
namespace {

uint32_t rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
}

Texture texture_from(uint32_t w, uint32_t h, const std::vector<uint8_t>& px, bool srgb) {
  return make_texture("test", w, h, px.data(), srgb);
}

// A 4 x 4 image: left half alpha 0, right half alpha 255; colour (200, 100, 50).
std::vector<uint8_t> half_transparent() {
  std::vector<uint8_t> px;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) px.insert(px.end(), {200, 100, 50, uint8_t(x < 2 ? 0 : 255)});
  return px;
}

std::string import_error(const std::vector<uint8_t>& image) {
  Scene s;
  try {
    import_gltf_bytes(s, test::to_glb(test::textured_quad_content(image)), "leaves.glb", ".", Mat4::identity());
  } catch (const SceneError& e) {
    EXPECT_TRUE(s.textures.empty() && s.materials.empty()) << "a failed import left content";
    return e.what();
  }
  return "<no error>";
}

TEST(Textures, MipChainKnownAnswers) {
  // 4 x 2 linear: level 1 is 2 x 1, level 2 1 x 1, each texel the mean of a 2 x 2 block.
  const std::vector<uint8_t> px = {0, 0, 0, 0,     4, 8, 0, 255,   100, 0, 0, 0,  100, 0, 0, 0,
                                   8, 16, 0, 255,  0, 0, 0, 255,   100, 0, 0, 0,  101, 0, 0, 0};
  const Texture t = texture_from(4, 2, px, false);
  ASSERT_EQ(t.mips.size(), 3u);
  ASSERT_EQ(t.mips[1].size(), 2u);
  ASSERT_EQ(t.mips[2].size(), 1u);
  EXPECT_EQ(t.mips[0][1], rgba(4, 8, 0, 255));
  EXPECT_EQ(t.mips[1][0], rgba(3, 6, 0, 191));   // (0+4+8+0)/4 = 3, (0+8+16+0)/4 = 6, 765/4 = 191.25
  EXPECT_EQ(t.mips[1][1], rgba(100, 0, 0, 0));   // 100.25 rounds down
  EXPECT_EQ(t.mips[2][0], rgba(52, 3, 0, 96));   // (3+100)/2 = 51.5 -> 52 (from the 8-bit level 1)
  EXPECT_EQ(t.bytes(), (8u + 2u + 1u) * 4u);
  // Odd sides: 3 x 3 -> 1 x 1 averages the top-left 2 x 2 block (edge texels repeat only
  // when a side is 1).
  std::vector<uint8_t> odd(9 * 4, 0);
  for (int i = 0; i < 9; ++i) odd[4 * i] = uint8_t(10 * i);
  const Texture o = texture_from(3, 3, odd, false);
  ASSERT_EQ(o.mips.size(), 2u);
  EXPECT_EQ(o.mips[1][0] & 0xffu, 20u);  // (0 + 10 + 30 + 40) / 4
  const Texture tall = texture_from(1, 4, std::vector<uint8_t>(16, 255), false);
  EXPECT_EQ(tall.mips.size(), 3u);  // 1x4, 1x2, 1x1
}

TEST(Textures, SrgbDecodesAndFiltersInLinearSpace) {
  EXPECT_EQ(srgb_to_linear(0), 0.0f);
  EXPECT_EQ(srgb_to_linear(255), 1.0f);
  EXPECT_NEAR(srgb_to_linear(188), 0.5029f, 1e-4f);
  EXPECT_NEAR(srgb_to_linear(10), 10.0f / 255.0f / 12.92f, 1e-7f);  // the linear toe
  for (int c = 0; c < 256; ++c) EXPECT_EQ(linear_to_srgb8(srgb_to_linear(uint8_t(c))), c) << c;
  // Black and white side by side: the sRGB mip is linear grey 0.5 (code 188), the linear one 128.
  const std::vector<uint8_t> bw = {0, 0, 0, 255, 255, 255, 255, 255};
  const Texture s = texture_from(2, 1, bw, true), l = texture_from(2, 1, bw, false);
  EXPECT_EQ(s.mips[1][0], rgba(188, 188, 188, 255));
  EXPECT_EQ(l.mips[1][0], rgba(128, 128, 128, 255));
  // Alpha is linear in both.
  const std::vector<uint8_t> a = {255, 255, 255, 0, 255, 255, 255, 255};
  EXPECT_EQ(texture_from(2, 1, a, true).mips[1][0] >> 24, 128u);
  // Fetches decode through the buffer's tables: code 188 is 0.5029 in sRGB, 188/255 linear.
  const std::vector<uint32_t> words = pack_textures({s, l});
  EXPECT_EQ(words[kTextureCountWord], 2u);
  EXPECT_EQ(texture_texel(words, 0, 1, 0, 0).x, srgb_to_linear(188));
  EXPECT_EQ(texture_texel(words, 1, 1, 0, 0).x, 128.0f / 255.0f);
  EXPECT_EQ(texture_texel(words, 0, 0, 1, 0).w, 1.0f);
}

TEST(Textures, BilinearWrapAndLevelKnownAnswers) {
  // 2 x 2 linear, red channel 0, 51, 102, 204 (codes exact in /255 steps of 0.2).
  const std::vector<uint8_t> px = {0, 0, 0, 255, 51, 0, 0, 255, 102, 0, 0, 255, 204, 0, 0, 255};
  const std::vector<uint32_t> w = pack_textures({texture_from(2, 2, px, false)});
  EXPECT_EQ(texture_bilinear(w, 0, 0, {0.25f, 0.25f}).x, 0.0f);          // a texel centre
  EXPECT_EQ(texture_bilinear(w, 0, 0, {0.75f, 0.75f}).x, 204.0f / 255);  // another
  EXPECT_NEAR(texture_bilinear(w, 0, 0, {0.5f, 0.5f}).x, (0 + 51 + 102 + 204) / 4.0f / 255, 1e-6f);
  // u = 0 lies between texel 1 (wrapped from the left) and texel 0.
  EXPECT_NEAR(texture_bilinear(w, 0, 0, {0.0f, 0.25f}).x, 25.5f / 255, 1e-6f);
  EXPECT_EQ(texture_bilinear(w, 0, 0, {2.25f, -0.75f}).x, 0.0f);  // repeats
  EXPECT_EQ(texture_bilinear(w, 0, 0, {NAN, 0.25f}).x, texture_bilinear(w, 0, 0, {0.0f, 0.25f}).x);
  EXPECT_EQ(texture_bilinear(w, 0, 7, {0.3f, 0.9f}).x, texture_bilinear(w, 0, 1, {0.1f, 0.2f}).x);  // clamped
  // Level: the nearest to log2 of the footprint in level-0 texels (64 x 64: 7 levels).
  const std::vector<uint32_t> big = pack_textures({texture_from(64, 64, std::vector<uint8_t>(64 * 64 * 4, 9), false)});
  auto level = [&](float texels) { return texture_level(big, 0, {texels / 64, 0}, {0, 0}); };
  EXPECT_EQ(level(0.0f), 0u);
  EXPECT_EQ(level(1.0f), 0u);
  EXPECT_EQ(level(1.41f), 0u);
  EXPECT_EQ(level(1.42f), 1u);
  EXPECT_EQ(level(2.0f), 1u);
  EXPECT_EQ(level(5.0f), 2u);
  EXPECT_EQ(level(1e6f), 6u);
  EXPECT_EQ(texture_level(big, 0, {0, 0}, {0, 4.0f / 64}), 2u);  // the longer derivative counts
  EXPECT_EQ(level(NAN), 0u);
}

TEST(Textures, DecodeAndLimits) {
  const DecodedImage d = decode_image(test::tga(4, 4, half_transparent()).data(), test::tga(4, 4, half_transparent()).size());
  ASSERT_TRUE(d.ok) << d.reason;
  EXPECT_EQ(d.width, 4u);
  EXPECT_EQ(d.rgba, half_transparent());
  const std::vector<uint8_t> junk = {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'};
  EXPECT_FALSE(decode_image(junk.data(), junk.size()).ok);
  // A header claiming 5000 x 8 texels: refused before any pixel is read.
  const DecodedImage big = decode_image(test::tga(5000, 8, {}).data(), 18);
  EXPECT_FALSE(big.ok);
  EXPECT_NE(big.reason.find("5000x8"), std::string::npos) << big.reason;
  EXPECT_THROW(make_texture("t", 0, 4, nullptr, false), std::invalid_argument);
  EXPECT_THROW(pack_textures(std::vector<Texture>(kTextureMaxCount + 1)), std::invalid_argument);
}

TEST(Textures, BadImagesAreOneLineNamingTheFile) {
  const std::string junk = import_error({'j', 'u', 'n', 'k', 0, 1, 2, 3});
  EXPECT_EQ(junk.rfind("leaves.glb: /images/0: expected an image stb_image can decode", 0), 0u) << junk;
  EXPECT_EQ(junk.find('\n'), std::string::npos);
  std::vector<uint8_t> huge = test::tga(4097, 2, std::vector<uint8_t>(4097 * 2 * 4, 255));
  const std::string big = import_error(huge);
  EXPECT_EQ(big.rfind("leaves.glb: /images/0: expected an image stb_image can decode, at most 4096 texels a side, got "
                      "an image of 4097x2 texels", 0), 0u) << big;
  // (A truncated TGA is not an error: stb_image reads its missing pixels as zeros.)
}

TEST(Textures, ImportedMaskSamplesTheTextureAlpha) {
  Scene s;
  const GltfImportReport r =
      import_gltf_bytes(s, test::to_glb(test::textured_quad_content(test::tga(4, 4, half_transparent()))), "leaves.glb",
                        ".", Mat4::identity());
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_TRUE(s.textures[0].srgb);
  EXPECT_EQ(s.textures[0].name, "leaves.glb: /images/0");
  EXPECT_EQ(r.texture_count, 1u);
  EXPECT_EQ(r.texture_bytes, (16u + 4u + 1u) * 4u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.texture, TextureKind::image);
  EXPECT_EQ(m.alpha, AlphaKind::texture_mask);
  EXPECT_EQ(m.base_color_texture, 0);
  EXPECT_TRUE(s.features().has(Feature::textured));
  EXPECT_TRUE(s.features().has(Feature::alpha_tested));

  const FlatScene flat = flatten(s, 0.0f);
  const GpuMaterial& g = flat.materials[0];
  EXPECT_NEAR(g.avg_opacity, 0.5f, 0.02f);  // baked from the texture's alpha
  // Albedo: the factor times the decoded sRGB texel (uv (0.875, 0.5): a right-half texel centre row).
  const Vec3 c = material_albedo(g, {0.875f, 0.625f}, &flat.textures);
  EXPECT_EQ(c.x, srgb_to_linear(200));
  EXPECT_EQ(c.z, srgb_to_linear(50));

  // Rays along -Z through the quad: x < 0.5 is the transparent half (uv.x = x).
  const Bvh bvh = build_bvh(flat);
  struct Ctx { const FlatScene* s; AlphaRay ray; } ctx{&flat, {}};
  AlphaTest alpha{[](const void* u, uint32_t tri, float bu, float bv) {
                    auto* c = const_cast<Ctx*>(static_cast<const Ctx*>(u));
                    return alpha_strategy_accept(*c->s, c->ray, tri, bu, bv, 0);
                  },
                  &ctx};
  auto hits = [&](float x, float y, uint32_t strategy) {
    const Ray ray{{x, y, 1}, {0, 0, -1}};
    ctx.ray = AlphaRay{strategy, 0, 0, alpha_ray_key(ray.origin, ray.dir)};
    return intersect_bvh(bvh, flat, ray, 0.0f, 10.0f, alpha).hit;
  };
  EXPECT_FALSE(hits(0.2f, 0.5f, 0));  // alpha test: through a transparent texel
  EXPECT_FALSE(hits(0.3f, 0.8f, 0));
  EXPECT_TRUE(hits(0.8f, 0.5f, 0));   // an opaque texel
  EXPECT_TRUE(hits(0.7f, 0.2f, 0));
  EXPECT_TRUE(hits(0.2f, 0.5f, 3));   // the opaque strategy ignores alpha
  // The dither strategy uses the baked 0.5: about half of many rays through one point hit.
  int dither_hits = 0;
  for (int i = 0; i < 1000; ++i) dither_hits += hits(0.2f + 1e-4f * float(i) / 1000, 0.5f, 1);
  EXPECT_GT(dither_hits, 400);
  EXPECT_LT(dither_hits, 600);
}

TEST(Textures, ExportRoundTripKeepsTexels) {
  Scene s;
  import_gltf_bytes(s, test::to_glb(test::textured_quad_content(test::tga(4, 4, half_transparent()))), "leaves.glb", ".",
                    Mat4::identity());
  const test::TempDir dir("textures_roundtrip");
  const std::string path = (dir.path() / "leaves.glb").string();
  export_gltf(s, path);
  Scene back;
  import_gltf(back, path, Mat4::identity());
  ASSERT_EQ(back.textures.size(), 1u);
  EXPECT_EQ(back.textures[0].mips, s.textures[0].mips);
  EXPECT_EQ(back.materials[0].alpha, AlphaKind::texture_mask);
  EXPECT_EQ(back.materials[0].alpha_cutoff, 0.5f);
  EXPECT_EQ(flatten(back, 0).textures, flatten(s, 0).textures);
}

}  // namespace
}  // namespace gib
