// Must round like textures.glsl (precise).
#include "renderer/scene/fp_contract_off.h"

#include "renderer/scene/texture.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace gib {
namespace {

uint32_t pack_rgba(const uint8_t c[4]) {
  return uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16 | uint32_t(c[3]) << 24;
}

uint8_t linear_to_unorm8(float v) {
  const float c = std::clamp(v, 0.0f, 1.0f) * 255.0f;
  return static_cast<uint8_t>(std::floor(c + 0.5f));
}

float bits_float(uint32_t b) {
  float f;
  std::memcpy(&f, &b, 4);
  return f;
}

uint32_t float_bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

// The next level down: each texel the mean of a 2x2 block (edge texels repeated for odd sizes),
// averaged in linear space.
std::vector<uint32_t> downsample(const std::vector<uint32_t>& src, uint32_t w, uint32_t h, bool srgb) {
  const uint32_t dw = std::max(1u, w / 2), dh = std::max(1u, h / 2);
  std::vector<uint32_t> dst(size_t(dw) * dh);
  for (uint32_t y = 0; y < dh; ++y)
    for (uint32_t x = 0; x < dw; ++x) {
      float sum[4] = {0, 0, 0, 0};
      for (uint32_t j = 0; j < 2; ++j)
        for (uint32_t i = 0; i < 2; ++i) {
          const uint32_t sx = std::min(2 * x + i, w - 1), sy = std::min(2 * y + j, h - 1);
          const uint32_t t = src[size_t(sy) * w + sx];
          for (int k = 0; k < 4; ++k) {
            const uint8_t code = uint8_t(t >> (8 * k));
            sum[k] += (srgb && k < 3) ? srgb_to_linear(code) : float(code) / 255.0f;
          }
        }
      uint8_t out[4];
      for (int k = 0; k < 4; ++k) {
        const float mean = sum[k] * 0.25f;
        out[k] = (srgb && k < 3) ? linear_to_srgb8(mean) : linear_to_unorm8(mean);
      }
      dst[size_t(y) * dw + x] = pack_rgba(out);
    }
  return dst;
}

struct Descriptor {
  uint32_t width, height, mips, first;
  bool srgb;
};

Descriptor descriptor(const std::vector<uint32_t>& words, uint32_t texture) {
  const uint32_t* d = &words.at(kTextureTableWord + 4 * size_t(texture));
  return {d[0], d[1], d[2] & 0x7fffffffu, d[3], (d[2] >> 31) != 0};
}

int32_t wrap(int32_t i, uint32_t n) {
  const int32_t m = int32_t(n);
  const int32_t r = i % m;
  return r < 0 ? r + m : r;
}

// uv - floor(uv), with anything outside [0, 1) (NaN, infinities, a rounding up to 1) at 0.
float wrap01(float u) {
  const float f = u - std::floor(u);
  return (f >= 0.0f && f < 1.0f) ? f : 0.0f;
}

}  // namespace

uint64_t Texture::bytes() const {
  uint64_t n = 0;
  for (const auto& m : mips) n += m.size() * 4;
  return n;
}

float srgb_to_linear(uint8_t code) {
  const double c = code / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

uint8_t linear_to_srgb8(float linear) {
  const double l = std::clamp(double(linear), 0.0, 1.0);
  const double s = l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::floor(s * 255.0 + 0.5));
}

DecodedImage decode_image(const uint8_t* bytes, size_t size) {
  DecodedImage out;
  if (bytes == nullptr || size == 0) {
    out.reason = "no bytes";
    return out;
  }
  if (size > size_t(std::numeric_limits<int>::max())) {
    out.reason = "an image of 2 GiB or more";
    return out;
  }
  int w = 0, h = 0, c = 0;
  // Checked before decoding, so an absurd header allocates nothing.
  if (!stbi_info_from_memory(bytes, int(size), &w, &h, &c)) {
    const char* why = stbi_failure_reason();
    out.reason = why ? why : "an unknown format";
    return out;
  }
  if (w <= 0 || h <= 0 || uint32_t(w) > kTextureMaxSize || uint32_t(h) > kTextureMaxSize) {
    out.reason = "an image of " + std::to_string(w) + "x" + std::to_string(h) + " texels (at most " +
                 std::to_string(kTextureMaxSize) + " a side)";
    return out;
  }
  stbi_uc* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &c, 4);
  if (pixels == nullptr) {
    const char* why = stbi_failure_reason();
    out.reason = why ? why : "a decode error";
    return out;
  }
  out.ok = true;
  out.width = uint32_t(w);
  out.height = uint32_t(h);
  out.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
  stbi_image_free(pixels);
  return out;
}

Texture make_texture(std::string name, uint32_t width, uint32_t height, const uint8_t* rgba, bool srgb) {
  if (width == 0 || height == 0 || width > kTextureMaxSize || height > kTextureMaxSize)
    throw std::invalid_argument(name + ": expected a texture of 1 to " + std::to_string(kTextureMaxSize) +
                                " texels a side, got " + std::to_string(width) + "x" + std::to_string(height));
  Texture t;
  t.name = std::move(name);
  t.width = width;
  t.height = height;
  t.srgb = srgb;
  std::vector<uint32_t> level(size_t(width) * height);
  for (size_t i = 0; i < level.size(); ++i) level[i] = pack_rgba(rgba + 4 * i);
  t.mips.push_back(std::move(level));
  uint32_t w = width, h = height;
  while (w > 1 || h > 1) {
    t.mips.push_back(downsample(t.mips.back(), w, h, srgb));
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
  }
  return t;
}

uint64_t textures_bytes(const std::vector<Texture>& textures) {
  uint64_t bytes = 0;
  for (const Texture& t : textures) bytes += t.bytes();
  return bytes;
}

std::vector<uint32_t> pack_textures(const std::vector<Texture>& textures) {
  if (textures.size() > kTextureMaxCount)
    throw std::invalid_argument("expected at most " + std::to_string(kTextureMaxCount) + " textures in a scene, got " +
                                std::to_string(textures.size()));
  const uint64_t bytes = textures_bytes(textures);
  if (bytes > kTextureMaxBytes)
    throw std::invalid_argument("expected at most " + std::to_string(kTextureMaxBytes >> 20) +
                                " MiB of textures and mips in a scene, got " + std::to_string(bytes) + " bytes");
  std::vector<uint32_t> words(kTextureTableWord + 4 * textures.size());
  for (uint32_t i = 0; i < 256; ++i) {
    words[i] = float_bits(srgb_to_linear(uint8_t(i)));
    words[256 + i] = float_bits(float(i) / 255.0f);
  }
  words[kTextureCountWord] = uint32_t(textures.size());
  words.reserve(words.size() + bytes / 4);
  for (size_t i = 0; i < textures.size(); ++i) {
    const Texture& t = textures[i];
    uint32_t* d = &words[kTextureTableWord + 4 * i];
    d[0] = t.width;
    d[1] = t.height;
    d[2] = uint32_t(t.mips.size()) | (t.srgb ? 0x80000000u : 0u);
    d[3] = uint32_t(words.size());
    for (const auto& m : t.mips) words.insert(words.end(), m.begin(), m.end());
  }
  return words;
}

Vec4 texture_texel(const std::vector<uint32_t>& words, uint32_t texture, uint32_t level, int32_t x, int32_t y) {
  const Descriptor d = descriptor(words, texture);
  level = std::min(level, d.mips - 1);
  uint32_t offset = d.first, w = d.width, h = d.height;
  for (uint32_t l = 0; l < level; ++l) {
    offset += w * h;
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
  }
  const uint32_t t = words.at(offset + uint32_t(wrap(y, h)) * w + uint32_t(wrap(x, w)));
  const uint32_t rgb_table = d.srgb ? 0u : 256u;
  return {bits_float(words[rgb_table + (t & 0xffu)]), bits_float(words[rgb_table + ((t >> 8) & 0xffu)]),
          bits_float(words[rgb_table + ((t >> 16) & 0xffu)]), bits_float(words[256u + (t >> 24)])};
}

Vec4 texture_bilinear(const std::vector<uint32_t>& words, uint32_t texture, uint32_t level, Vec2 uv) {
  const Descriptor d = descriptor(words, texture);
  level = std::min(level, d.mips - 1);
  const uint32_t w = std::max(1u, d.width >> level), h = std::max(1u, d.height >> level);
  const float x = wrap01(uv.x) * float(w) - 0.5f;
  const float y = wrap01(uv.y) * float(h) - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int32_t ix = int32_t(x0), iy = int32_t(y0);
  const Vec4 c00 = texture_texel(words, texture, level, ix, iy);
  const Vec4 c10 = texture_texel(words, texture, level, ix + 1, iy);
  const Vec4 c01 = texture_texel(words, texture, level, ix, iy + 1);
  const Vec4 c11 = texture_texel(words, texture, level, ix + 1, iy + 1);
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  auto mix2 = [&](float a, float b, float c, float e) { return lerp(lerp(a, b, fx), lerp(c, e, fx), fy); };
  return {mix2(c00.x, c10.x, c01.x, c11.x), mix2(c00.y, c10.y, c01.y, c11.y), mix2(c00.z, c10.z, c01.z, c11.z),
          mix2(c00.w, c10.w, c01.w, c11.w)};
}

uint32_t texture_level(const std::vector<uint32_t>& words, uint32_t texture, Vec2 duv_dx, Vec2 duv_dy) {
  const Descriptor d = descriptor(words, texture);
  const float sw = float(d.width), sh = float(d.height);
  const float ax = duv_dx.x * sw, ay = duv_dx.y * sh, bx = duv_dy.x * sw, by = duv_dy.y * sh;
  const float rho2 = std::max(ax * ax + ay * ay, bx * bx + by * by);
  // Level l is nearest when rho is in [2^(l - 1/2), 2^(l + 1/2)): rho^2 >= 2^(2l - 1).
  uint32_t level = 0;
  float bound = 2.0f;  // 2^(2l - 1) for l = 1
  while (level + 1 < d.mips && rho2 >= bound) {
    ++level;
    bound *= 4.0f;
  }
  return level;
}

}  // namespace gib
