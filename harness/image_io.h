// Image files through OpenImageIO: EXR for linear data, PNG for a tone-mapped preview.
#pragma once
#include <string>

#include "renderer/graph/executor.h"

namespace gib {

// Writes a float EXR (1-4 channels as the image has; 2 channels are written as R,G).
// Written to a temporary file in the same folder and renamed, so a failure never leaves a
// partial file under the final name. Throws std::runtime_error naming the path.
void write_exr(const std::string& path, const FloatImage& image);
// Preview: exposure 1, clamp, sRGB encode, 8-bit PNG. Same atomic write.
void write_png_preview(const std::string& path, const FloatImage& image);
FloatImage read_image(const std::string& path);  // EXR or PNG, as float RGBA/RGB

}  // namespace gib
