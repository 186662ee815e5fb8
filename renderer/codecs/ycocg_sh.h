// YCoCg spherical-harmonic radiance in 64 bits (AC Shadows RTGI, "Lighting": "YCoCg (order 1
// for Y, order 0 for CoCg), 64 bits (6 x 8 bits + 16 magnitude)"): CPU mirror of
// renderer/shaders/include/ycocg_sh.glsl, bit for bit (tests/test_probe_volume.cpp runs both).
//
// Six values: Y0 (>= 0), the Y band-1 vector (x, y, z), Co, Cg. They are divided by a shared
// power-of-two magnitude 2^e, e the smallest integer with 2^e >= the largest |value|, and
// rounded half up: Y0 to unorm8 (q / 255), the others to biased snorm8 ((q - 127) / 127).
// Word 0: Y0 | Y1x << 8 | Y1y << 16 | Y1z << 24; word 1: Co | Cg << 8 | (e + 128) << 16.
// A power of two (not any 16-bit value) so that encoding needs only exact scalings and single
// correctly rounded operations, never a division (2.5 ulp on a GPU): both sides agree exactly;
// the cost is up to one bit of the largest value's precision. Non-finite values and values whose
// magnitude is below 2^-100 encode as 0; e is clamped to [-100, 127]. Negative Y0 clamps to 0.
#pragma once
#include <array>
#include <cstdint>

namespace gib::codecs {

// y0, y1x, y1y, y1z, co, cg
using YcocgSh = std::array<float, 6>;

std::array<uint32_t, 2> pack_ycocg_sh(const YcocgSh& v);
YcocgSh unpack_ycocg_sh(const std::array<uint32_t, 2>& w);

// RGB <-> YCoCg: Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4.
std::array<float, 3> rgb_to_ycocg(float r, float g, float b);
std::array<float, 3> ycocg_to_rgb(float y, float co, float cg);

}  // namespace gib::codecs
