// Image files through OpenImageIO: EXR for linear data, PNG for a tone-mapped preview.
#pragma once
#include <string>

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
// EXR or PNG, as float RGBA/RGB; *half (if given): the file stores half floats.
FloatImage read_image(const std::string& path, bool* half = nullptr);

}  // namespace gib
