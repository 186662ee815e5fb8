#include "renderer/codecs/sh2.h"

namespace gib::codecs {

Vec4 sh2_basis(Vec3 d) { return {kShY0, kShY1 * d.y, kShY1 * d.z, kShY1 * d.x}; }

Vec4 sh2_project(Vec3 d, float v) {
  const Vec4 b = sh2_basis(d);
  return {b.x * v, b.y * v, b.z * v, b.w * v};
}

float sh2_eval(Vec4 sh, Vec3 d) {
  const Vec4 b = sh2_basis(d);
  return sh.x * b.x + sh.y * b.y + sh.z * b.z + sh.w * b.w;
}

float sh2_irradiance(Vec4 sh, Vec3 n) {
  // A0 / pi = 1, A1 / pi = 2/3.
  const Vec4 b = sh2_basis(n);
  return sh.x * b.x + (2.0f / 3.0f) * (sh.y * b.y + sh.z * b.z + sh.w * b.w);
}

}  // namespace gib::codecs
