// Image textures: RGBA8 images with a full mip chain built on the CPU, packed
// into one storage buffer that every pass binds with the scene (scene.glsl, gib_textures), and
// the CPU mirror of the shaders' fetch and filter (renderer/shaders/include/textures.glsl: same
// layout, same operation order, arithmetic that rounds the same, so tests compare bit for bit).
//
// Colour spaces follow glTF: base colour and emissive images are sRGB, metallic-roughness,
// normal and occlusion images linear. A texel is stored as its 8-bit code and decoded through a
// 256-entry table of floats held in the buffer itself (sRGB codes to linear, linear codes / 255),
// so the GPU and the CPU decode exactly alike. Mips are box filtered (2x2, edge texels repeated
// for odd sizes) in linear space and encoded back to 8 bits with rounding.
//
// Packed buffer (uint words):
//   [0, 256)        sRGB code -> linear float bits      [256, 512)  code / 255 float bits
//   [512]           texture count N
//   [513 + 4 i ..]  texture i: width, height, mip count | (srgb << 31), first texel word
//   then texels, one RGBA8 word each (r in the low byte), texture by texture, level 0 first,
//   rows top to bottom (v = 0 is the first row, as glTF's uv origin is the image's top left).
// Sampling wraps (glTF's default REPEAT sampler; others are treated as REPEAT, noted by the
// import): bilinear within one mip level; the level is the one nearest log2 of the footprint.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/math.h"

namespace gib {

struct Texture {
  std::string name;  // where it came from, for messages ("atrium.glb: /images/0")
  uint32_t width = 0, height = 0;
  bool srgb = false;
  std::vector<std::vector<uint32_t>> mips;  // RGBA8 words, level 0 first, down to 1x1
  uint64_t bytes() const;                   // texel bytes of every level
};
// Texel bytes of every texture and mip (what kTextureMaxBytes bounds).
uint64_t textures_bytes(const std::vector<Texture>& textures);

inline constexpr uint32_t kTextureMaxSize = 4096;                 // texels per side
inline constexpr uint32_t kTextureMaxCount = 1024;                // per scene
inline constexpr uint64_t kTextureMaxBytes = uint64_t{256} << 20;  // every texture and mip of a scene
inline constexpr uint32_t kTextureNone = 0xffffffffu;             // GpuMaterial: no texture

inline constexpr uint32_t kTextureLutWords = 512;                  // both decode tables
inline constexpr uint32_t kTextureCountWord = kTextureLutWords;     // N
inline constexpr uint32_t kTextureTableWord = kTextureLutWords + 1;  // descriptors, 4 words each

// Decoded pixels (stb_image, forced to 4 channels) or why not. No limits checked here.
struct DecodedImage {
  bool ok = false;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
  std::string reason;
};
DecodedImage decode_image(const uint8_t* bytes, size_t size);

// A texture with its mip chain from RGBA8 pixels (width * height * 4 bytes). Throws
// std::invalid_argument naming `name` when a side is 0 or above kTextureMaxSize.
Texture make_texture(std::string name, uint32_t width, uint32_t height, const uint8_t* rgba, bool srgb);

// The decode tables' entries (float): sRGB code -> linear, and the inverse encode with rounding.
float srgb_to_linear(uint8_t code);
uint8_t linear_to_srgb8(float linear);

// The storage buffer for `textures`. Throws std::invalid_argument when the count or the bytes
// exceed the limits above.
std::vector<uint32_t> pack_textures(const std::vector<Texture>& textures);

// ---- CPU mirror of textures.glsl (words: pack_textures' output) ----
// One texel of `level` at integer (x, y), wrapped; decoded to linear floats.
Vec4 texture_texel(const std::vector<uint32_t>& words, uint32_t texture, uint32_t level, int32_t x, int32_t y);
// Bilinear at uv within `level` (clamped to the chain), wrapped.
Vec4 texture_bilinear(const std::vector<uint32_t>& words, uint32_t texture, uint32_t level, Vec2 uv);
// The mip level for a pixel footprint (uv derivatives): the nearest to log2 of the longer
// derivative in level-0 texels, found by exact comparisons with powers of two.
uint32_t texture_level(const std::vector<uint32_t>& words, uint32_t texture, Vec2 duv_dx, Vec2 duv_dy);

}  // namespace gib
