// Image files: EXR for linear data (OpenEXR, libopenexr-dev), PNG for a tone-mapped preview and
// 8-bit inputs (stb_image / stb_image_write, libstb-dev).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/graph/executor.h"

namespace gib {

// Writes a float EXR (1-4 channels as the image has; 2 channels are written as R,G).
// Written to a temporary file in the same folder and renamed, so a failure never leaves a
// partial file under the final name. Throws std::runtime_error naming the path.
// half: stored as binary16, each value rounded as codecs::float_to_half (ties to even), so a
// reader can reproduce the stored value exactly (round_to_half below).
void write_exr(const std::string& path, const FloatImage& image, bool half = false);
// Whether every finite value of the image is finite in half (|v| < 65520).
bool fits_half(const FloatImage& image);
// Every value rounded to binary16 and back: what a half EXR stores.
FloatImage round_to_half(const FloatImage& image);
// Preview: exposure 1, clamp, sRGB encode, 8-bit PNG. Same atomic write.
void write_png_preview(const std::string& path, const FloatImage& image);
// EXR (told by its magic number; channels R, G, B, A as present, else its one channel as grey)
// or an 8-bit image stb_image decodes (PNG, JPEG, ...: values / 255, no transfer function), as
// float; *half (if given): the EXR stores half floats. Throws naming the path.
FloatImage read_image(const std::string& path, bool* half = nullptr);
// An 8-bit image (PNG, JPEG, BMP, TGA) as RGB bytes (grey replicated, alpha dropped).
struct Rgb8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;
};
Rgb8Image read_rgb8(const std::string& path);

}  // namespace gib
