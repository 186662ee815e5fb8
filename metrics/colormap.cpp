#include "metrics/colormap.h"

#include <algorithm>
#include <cmath>

namespace gib {
namespace {

// Magma as 17 control points (t = i/16), sRGB-encoded, interpolated piecewise linearly.
// The points are our own approximation of the magma curve's appearance: near-black blue at
// 0, deep purple (~0.25), magenta-red (~0.5), orange (~0.75), pale yellow at 1. Luminance
// increases monotonically along the table, which is the property the error maps rely on;
// the exact colours are not meant to match matplotlib's table to more than about 0.01.
constexpr int kMagmaPoints = 17;
constexpr float kMagma[kMagmaPoints][3] = {
    {0.0015f, 0.0005f, 0.0139f},  // 0/16
    {0.0470f, 0.0340f, 0.1560f},  // 1/16
    {0.1130f, 0.0650f, 0.2770f},  // 2/16
    {0.2120f, 0.0610f, 0.4040f},  // 3/16
    {0.3160f, 0.0720f, 0.4850f},  // 4/16
    {0.4140f, 0.1020f, 0.5060f},  // 5/16
    {0.5120f, 0.1300f, 0.5050f},  // 6/16
    {0.6140f, 0.1700f, 0.4950f},  // 7/16
    {0.7160f, 0.2150f, 0.4750f},  // 8/16
    {0.8160f, 0.2580f, 0.4370f},  // 9/16
    {0.9040f, 0.3190f, 0.3880f},  // 10/16
    {0.9600f, 0.4170f, 0.3600f},  // 11/16
    {0.9870f, 0.5360f, 0.3820f},  // 12/16
    {0.9960f, 0.6460f, 0.4400f},  // 13/16
    {0.9960f, 0.7620f, 0.5300f},  // 14/16
    {0.9920f, 0.8750f, 0.6350f},  // 15/16
    {0.9870f, 0.9910f, 0.7490f},  // 16/16
};

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace

std::array<float, 3> magma(float t) {
  if (!(t > 0.0f)) t = 0.0f;  // also NaN
  if (t > 1.0f) t = 1.0f;
  float s = t * float(kMagmaPoints - 1);
  int i = std::min(int(s), kMagmaPoints - 2);
  float f = s - float(i);
  std::array<float, 3> rgb{};
  for (int c = 0; c < 3; ++c) rgb[c] = kMagma[i][c] + f * (kMagma[i + 1][c] - kMagma[i][c]);
  return rgb;
}

FloatImage magma_error_map(const FloatImage& error, bool linear_output) {
  FloatImage out(error.width, error.height, 3);
  const size_t n = error.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    auto rgb = magma(error.channels ? error.pixels[i * error.channels] : 0.0f);
    for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = linear_output ? srgb_to_linear(rgb[c]) : rgb[c];
  }
  return out;
}

}  // namespace gib
