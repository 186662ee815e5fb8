// A CPU image of floats: readbacks, files and every metric work on this.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gib {

struct FloatImage {
  uint32_t width = 0, height = 0, channels = 4;
  std::vector<float> pixels;  // row-major, `channels` floats per pixel
  FloatImage() = default;
  FloatImage(uint32_t w, uint32_t h, uint32_t c, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}
  float at(uint32_t x, uint32_t y, uint32_t c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
  float& at(uint32_t x, uint32_t y, uint32_t c) { return pixels[(size_t(y) * width + x) * channels + c]; }
  size_t pixel_count() const { return size_t(width) * height; }
};

}  // namespace gib
