// Two-band (l <= 1, 4 coefficients) real spherical harmonics: the CPU mirror of
// renderer/shaders/include/sh.glsl.
//
// Coefficient order (a vec4 / Vec4 x, y, z, w): Y00, Y1-1, Y10, Y11 with
//   Y00 = 0.282095, Y1-1 = 0.488603 * d.y, Y10 = 0.488603 * d.z, Y11 = 0.488603 * d.x.
// (So w, the last, multiplies x: the usual l,m ordering, not x,y,z order.)
// A signal's coefficients are its projections c_lm = integral of L(w) Y_lm(w) dw over the
// sphere; sh2_project(d, v) = v * basis(d) is one sample's share, to be scaled by its solid
// angle (4 pi / N for N uniform directions).
// sh2_irradiance(c, n) returns irradiance / pi, i.e. the outgoing radiance of a white
// Lambertian surface with normal n: (pi c00 Y00 + 2pi/3 sum_m c1m Y1m(n)) / pi (cosine-lobe
// convolution, A0 = pi, A1 = 2 pi / 3). Constant radiance L gives L; a directional source of
// irradiance E0 from l gives E0/pi (1/4 + cos/2) vs the true E0/pi max(0, cos): error <= E0/(4 pi).
#pragma once
#include "renderer/scene/math.h"

namespace gib::codecs {

inline constexpr float kShY0 = 0.282095f;  // 1 / (2 sqrt(pi))
inline constexpr float kShY1 = 0.488603f;  // sqrt(3) / (2 sqrt(pi))

Vec4 sh2_basis(Vec3 d);                      // d unit
Vec4 sh2_project(Vec3 d, float value);       // value * sh2_basis(d)
float sh2_eval(Vec4 sh, Vec3 d);             // reconstructed signal in direction d
float sh2_irradiance(Vec4 sh, Vec3 n);       // irradiance / pi (see above)

}  // namespace gib::codecs
