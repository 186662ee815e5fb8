// Texel decoding for readbacks and --dump: every image format to floats.
#include <fmt/format.h>

#include <cstring>

#include "renderer/codecs/packed_float.h"
#include "renderer/graph/executor.h"

namespace gib {

FloatImage decode_texels(Format format, uint32_t width, uint32_t height, const std::vector<uint8_t>& raw) {
  FloatImage out;
  out.width = width;
  out.height = height;
  size_t n = size_t(width) * height;
  auto u32 = [&](size_t i) { uint32_t v; std::memcpy(&v, raw.data() + i * 4, 4); return v; };
  auto f32 = [&](size_t i) { float v; std::memcpy(&v, raw.data() + i * 4, 4); return v; };
  auto f16 = [&](size_t i) { uint16_t v; std::memcpy(&v, raw.data() + i * 2, 2); return codecs::half_to_float(v); };
  size_t expect = n * format_bytes_per_texel(format);
  if (raw.size() != expect)
    throw GraphError(fmt::format("readback: {} image {}x{} expected {} bytes, got {}", format_name(format), width, height,
                                 expect, raw.size()));
  auto fill = [&](uint32_t channels, auto&& texel) {
    out.channels = channels;
    out.pixels.resize(n * channels);
    for (size_t i = 0; i < n; ++i) texel(i, &out.pixels[i * channels]);
  };
  switch (format) {
    case Format::r32_uint: fill(1, [&](size_t i, float* p) { p[0] = float(u32(i)); }); break;
    case Format::rg32_uint: fill(2, [&](size_t i, float* p) { p[0] = float(u32(2 * i)); p[1] = float(u32(2 * i + 1)); }); break;
    case Format::rgba32_uint: fill(4, [&](size_t i, float* p) { for (int c = 0; c < 4; ++c) p[c] = float(u32(4 * i + c)); }); break;
    case Format::r32_float:
    case Format::d32_float: fill(1, [&](size_t i, float* p) { p[0] = f32(i); }); break;
    case Format::rg32_float: fill(2, [&](size_t i, float* p) { p[0] = f32(2 * i); p[1] = f32(2 * i + 1); }); break;
    case Format::rgba32_float: fill(4, [&](size_t i, float* p) { for (int c = 0; c < 4; ++c) p[c] = f32(4 * i + c); }); break;
    case Format::rg16_float: fill(2, [&](size_t i, float* p) { p[0] = f16(2 * i); p[1] = f16(2 * i + 1); }); break;
    case Format::rgba16_float: fill(4, [&](size_t i, float* p) { for (int c = 0; c < 4; ++c) p[c] = f16(4 * i + c); }); break;
    case Format::rgba16_uint:
      fill(4, [&](size_t i, float* p) { for (int c = 0; c < 4; ++c) p[c] = float(uint32_t(raw[8 * i + 2 * c]) | uint32_t(raw[8 * i + 2 * c + 1]) << 8); });
      break;
    case Format::rgba8_unorm: fill(4, [&](size_t i, float* p) { for (int c = 0; c < 4; ++c) p[c] = raw[4 * i + c] / 255.0f; }); break;
    case Format::b10g11r11_float: fill(3, [&](size_t i, float* p) { codecs::decode_r11g11b10(u32(i), p); }); break;
    case Format::e5b9g9r9_float: fill(3, [&](size_t i, float* p) { codecs::decode_rgb9e5(u32(i), p); }); break;
    case Format::buffer: throw GraphError("readback: a buffer is not an image");
  }
  return out;
}

}  // namespace gib
