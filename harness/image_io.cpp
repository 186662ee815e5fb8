#include "harness/image_io.h"

#include "renderer/codecs/half.h"

#include <fmt/format.h>

#include <OpenImageIO/imageio.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace gib {
namespace {

void write_atomic(const std::string& path, const OIIO::ImageSpec& spec, const void* data) {
  namespace fs = std::filesystem;
  fs::path final_path(path);
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path());
  // Same extension so OIIO picks the right writer for the temporary file.
  fs::path tmp = final_path.parent_path() / fmt::format(".{}.tmp{}{}", final_path.stem().string(), getpid(),
                                                         final_path.extension().string());
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw std::runtime_error(fmt::format("{}: cannot create an image writer: {}", path, OIIO::geterror()));
  if (!out->open(tmp.string(), spec) || !out->write_image(spec.format, data) || !out->close()) {
    std::string err = out->geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format("{}: write failed: {}", path, err));
  }
  fs::rename(tmp, final_path);
}

}  // namespace

void write_exr(const std::string& path, const FloatImage& img, bool half) {
  OIIO::ImageSpec spec(int(img.width), int(img.height), int(img.channels),
                       half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  static const char* kNames[] = {"R", "G", "B", "A"};
  spec.channelnames.assign(kNames, kNames + img.channels);
  spec.alpha_channel = img.channels == 4 ? 3 : -1;
  spec.attribute("compression", "zip");
  if (!half) return write_atomic(path, spec, img.pixels.data());
  // Our own rounding (the GPU codecs' CPU mirror), not the library's, so round_to_half is exact.
  std::vector<uint16_t> bits(img.pixels.size());
  for (size_t i = 0; i < bits.size(); ++i) bits[i] = codecs::float_to_half(img.pixels[i]);
  write_atomic(path, spec, bits.data());
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
  OIIO::ImageSpec spec(int(img.width), int(img.height), 3, OIIO::TypeDesc::UINT8);
  write_atomic(path, spec, rgb.data());
}

FloatImage read_image(const std::string& path, bool* half) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read image: {}", path, OIIO::geterror()));
  const auto& spec = in->spec();
  if (half) *half = spec.format == OIIO::TypeDesc::HALF;
  FloatImage img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.channels = uint32_t(std::min(spec.nchannels, 4));
  img.pixels.resize(size_t(img.width) * img.height * img.channels);
  if (!in->read_image(0, 0, 0, int(img.channels), OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw std::runtime_error(fmt::format("{}: corrupt or unreadable image: {}", path, in->geterror()));
  return img;
}

}  // namespace gib
