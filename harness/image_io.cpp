#include "harness/image_io.h"

#include "renderer/codecs/half.h"

#include <fmt/format.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace gib {
namespace {

namespace fs = std::filesystem;
constexpr std::array<const char*, 4> kChannelNames = {"R", "G", "B", "A"};

// Writes through `write(tmp)` into a temporary file beside `path` and renames it, so a failure
// never leaves a partial file under the final name.
template <typename Write>
void write_atomic(const std::string& path, Write write) {
  fs::path final_path(path);
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path());
  fs::path tmp = final_path.parent_path() / fmt::format(".{}.tmp{}{}", final_path.stem().string(), getpid(),
                                                         final_path.extension().string());
  try {
    write(tmp.string());
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format("{}: write failed: {}", path, e.what()));
  }
  fs::rename(tmp, final_path);
}

// The first 4 bytes of an OpenEXR file.
bool has_exr_magic(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char m[4] = {};
  return f.read(reinterpret_cast<char*>(m), 4) && m[0] == 0x76 && m[1] == 0x2f && m[2] == 0x31 && m[3] == 0x01;
}

// The EXR channels read, in image order: R, G, B, A where present (a file of one channel Y or
// any other single name reads as grey). Throws naming what was expected.
std::vector<std::string> exr_channels(const std::string& path, const Imf::ChannelList& list) {
  std::vector<std::string> names;
  for (const char* n : kChannelNames)
    if (list.findChannel(n)) names.push_back(n);
  if (names.empty()) {
    auto it = list.begin();
    if (it == list.end()) throw std::runtime_error(fmt::format("{}: expected an EXR with channels R, G, B or A, got none", path));
    names.push_back(it.name());
  }
  return names;
}

FloatImage read_exr(const std::string& path, bool* half) {
  try {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    if (w <= 0 || h <= 0) throw std::runtime_error("empty data window");
    const std::vector<std::string> names = exr_channels(path, in.header().channels());
    FloatImage img{uint32_t(w), uint32_t(h), uint32_t(names.size())};
    Imf::FrameBuffer fb;
    const size_t xs = sizeof(float) * img.channels, ys = xs * img.width;
    char* base = reinterpret_cast<char*>(img.pixels.data()) - (ptrdiff_t(dw.min.x) * xs + ptrdiff_t(dw.min.y) * ys);
    bool all_half = true;
    for (size_t c = 0; c < names.size(); ++c) {
      all_half &= in.header().channels().findChannel(names[c])->type == Imf::HALF;
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    if (half) *half = all_half;
    return img;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: corrupt or unreadable EXR: {}", path, e.what()));
  }
}

}  // namespace

void write_exr(const std::string& path, const FloatImage& img, bool half) {
  if (img.channels < 1 || img.channels > 4 || img.pixels.size() != size_t(img.width) * img.height * img.channels)
    throw std::runtime_error(fmt::format("{}: expected an image of 1-4 channels with width x height x channels values", path));
  // Our own rounding (the GPU codecs' CPU mirror), not the library's, so round_to_half is exact.
  std::vector<uint16_t> bits;
  if (half) {
    bits.resize(img.pixels.size());
    for (size_t i = 0; i < bits.size(); ++i) bits[i] = codecs::float_to_half(img.pixels[i]);
  }
  write_atomic(path, [&](const std::string& tmp) {
    Imf::Header header(int(img.width), int(img.height));
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const size_t elem = half ? sizeof(uint16_t) : sizeof(float);
    const size_t xs = elem * img.channels, ys = xs * img.width;
    const char* base = half ? reinterpret_cast<const char*>(bits.data()) : reinterpret_cast<const char*>(img.pixels.data());
    for (uint32_t c = 0; c < img.channels; ++c) {
      header.channels().insert(kChannelNames[c], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
      fb.insert(kChannelNames[c], Imf::Slice(half ? Imf::HALF : Imf::FLOAT, const_cast<char*>(base + c * elem), xs, ys));
    }
    Imf::OutputFile out(tmp.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(int(img.height));
  });
}

bool fits_half(const FloatImage& img) {
  for (float v : img.pixels)
    if (std::isfinite(v) && std::abs(v) >= 65520.0f) return false;
  return true;
}

FloatImage round_to_half(const FloatImage& img) {
  FloatImage out = img;
  for (float& v : out.pixels) v = codecs::half_to_float(codecs::float_to_half(v));
  return out;
}

void write_png_preview(const std::string& path, const FloatImage& img) {
  std::vector<uint8_t> rgb(size_t(img.width) * img.height * 3);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
    for (uint32_t c = 0; c < 3; ++c) {
      float v = img.pixels[i * img.channels + std::min(c, img.channels - 1)];
      if (!std::isfinite(v)) v = 0;
      v = std::clamp(v, 0.0f, 1.0f);
      v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
      rgb[i * 3 + c] = static_cast<uint8_t>(std::lround(v * 255.0f));
    }
  write_atomic(path, [&](const std::string& tmp) {
    if (!stbi_write_png(tmp.c_str(), int(img.width), int(img.height), 3, rgb.data(), int(img.width) * 3))
      throw std::runtime_error("stb_image_write could not write the PNG");
  });
}

Rgb8Image read_rgb8(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (!data)
    throw std::runtime_error(fmt::format("{}: corrupt or unreadable image (expected PNG, JPEG, BMP or TGA): {}", path,
                                         stbi_failure_reason() ? stbi_failure_reason() : "unknown"));
  Rgb8Image out{uint32_t(w), uint32_t(h), std::vector<uint8_t>(data, data + size_t(w) * h * 3)};
  stbi_image_free(data);
  return out;
}

FloatImage read_image(const std::string& path, bool* half) {
  if (!fs::exists(path)) throw std::runtime_error(fmt::format("{}: cannot read image: no such file", path));
  if (has_exr_magic(path)) return read_exr(path, half);
  int w = 0, h = 0, n = 0;
  if (!stbi_info(path.c_str(), &w, &h, &n))
    throw std::runtime_error(fmt::format("{}: corrupt or unreadable image (expected EXR or PNG): {}", path,
                                         stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
  const int channels = n == 2 ? 2 : std::min(std::max(n, 1), 4);
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, channels);
  if (!data) throw std::runtime_error(fmt::format("{}: corrupt or unreadable image: {}", path, stbi_failure_reason()));
  FloatImage img{uint32_t(w), uint32_t(h), uint32_t(channels)};
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(data[i]) / 255.0f;
  stbi_image_free(data);
  if (half) *half = false;
  return img;
}

}  // namespace gib
