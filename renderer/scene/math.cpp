#include "renderer/scene/math.h"

#include <numbers>

namespace gib {

namespace {
constexpr float kDegToRad = std::numbers::pi_v<float> / 180.0f;
}

Mat4 Mat4::rotation_x(float rad) {
  Mat4 r = identity();
  float c = std::cos(rad), s = std::sin(rad);
  r.m[1][1] = c; r.m[1][2] = s;
  r.m[2][1] = -s; r.m[2][2] = c;
  return r;
}

Mat4 Mat4::rotation_y(float rad) {
  Mat4 r = identity();
  float c = std::cos(rad), s = std::sin(rad);
  r.m[0][0] = c; r.m[0][2] = -s;
  r.m[2][0] = s; r.m[2][2] = c;
  return r;
}

Mat4 Mat4::rotation_z(float rad) {
  Mat4 r = identity();
  float c = std::cos(rad), s = std::sin(rad);
  r.m[0][0] = c; r.m[0][1] = s;
  r.m[1][0] = -s; r.m[1][1] = c;
  return r;
}

Mat4 Mat4::trs(Vec3 t, Vec3 rotation_deg, Vec3 s) {
  return translation(t) * rotation_x(rotation_deg.x * kDegToRad) *
         rotation_y(rotation_deg.y * kDegToRad) * rotation_z(rotation_deg.z * kDegToRad) * scaling(s);
}

Mat4 Mat4::look_at(Vec3 eye, Vec3 target, Vec3 up) {
  Vec3 f = normalize(target - eye);
  if (length(f) == 0.0f) f = {0, 0, -1};  // eye == target: keep a valid basis, look down -Z
  Vec3 s = cross(f, up);
  // Looking straight along `up` (e.g. a camera looking down at a floor) leaves the roll
  // undefined; pick a fixed fallback so the matrix stays orthonormal instead of NaN.
  if (length(s) < 1e-6f * std::fmax(length(up), 1e-30f)) {
    Vec3 alt = std::fabs(f.z) < 0.9f ? Vec3{0, 0, -1} : Vec3{0, 1, 0};
    s = cross(f, alt);
  }
  s = normalize(s);
  Vec3 u = cross(s, f);
  Mat4 r = identity();
  r.m[0][0] = s.x; r.m[1][0] = s.y; r.m[2][0] = s.z;
  r.m[0][1] = u.x; r.m[1][1] = u.y; r.m[2][1] = u.z;
  r.m[0][2] = -f.x; r.m[1][2] = -f.y; r.m[2][2] = -f.z;
  r.m[3][0] = -dot(s, eye);
  r.m[3][1] = -dot(u, eye);
  r.m[3][2] = dot(f, eye);
  return r;
}

Mat4 Mat4::perspective(float fov_y_rad, float aspect, float near_plane, float far_plane) {
  // View space looks down -Z; Vulkan NDC has y pointing down and depth in [0, 1], so the
  // y scale is negated and z maps -near -> 0, -far -> 1.
  float f = 1.0f / std::tan(0.5f * fov_y_rad);
  Mat4 r;
  r.m[0][0] = f / aspect;
  r.m[1][1] = -f;
  r.m[2][2] = far_plane / (near_plane - far_plane);
  r.m[2][3] = -1.0f;
  r.m[3][2] = near_plane * far_plane / (near_plane - far_plane);
  return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) sum += a.m[k][row] * b.m[c][k];
      r.m[c][row] = sum;
    }
  return r;
}

// Affine use: w is taken as 1 and the result is not divided by w; projective transforms go
// through transform(Vec4).
Vec3 Mat4::transform_point(Vec3 p) const {
  return {m[0][0] * p.x + m[1][0] * p.y + m[2][0] * p.z + m[3][0],
          m[0][1] * p.x + m[1][1] * p.y + m[2][1] * p.z + m[3][1],
          m[0][2] * p.x + m[1][2] * p.y + m[2][2] * p.z + m[3][2]};
}

Vec3 Mat4::transform_vector(Vec3 v) const {
  return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
          m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
          m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
}

Vec4 Mat4::transform(Vec4 v) const {
  float in[4] = {v.x, v.y, v.z, v.w};
  float out[4] = {};
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 4; ++c) out[row] += m[c][row] * in[c];
  return {out[0], out[1], out[2], out[3]};
}

// Cofactor expansion in double: far-from-origin worlds put large translations next to small
// rotations, and float cancellation there is visible. A singular (or non-finite) matrix
// yields the zero matrix rather than Inf/NaN, so callers never propagate NaN.
Mat4 Mat4::inverse() const {
  double a[16];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a[c * 4 + r] = m[c][r];
  double inv[16];
  inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] + a[9] * a[7] * a[14] +
           a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
  inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] - a[8] * a[7] * a[14] -
           a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
  inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] + a[8] * a[7] * a[13] +
           a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
  inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] - a[8] * a[6] * a[13] -
            a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
  inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] - a[9] * a[3] * a[14] -
           a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
  inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] + a[8] * a[3] * a[14] +
           a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
  inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] - a[8] * a[3] * a[13] -
           a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
  inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] + a[8] * a[2] * a[13] +
            a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
  inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] + a[5] * a[3] * a[14] +
           a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
  inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] - a[4] * a[3] * a[14] -
           a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
  inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] + a[4] * a[3] * a[13] +
            a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
  inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] - a[4] * a[2] * a[13] -
            a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
  inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] - a[5] * a[3] * a[10] -
           a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
  inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] + a[4] * a[3] * a[10] +
           a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
  inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] - a[4] * a[3] * a[9] -
            a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
  inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] + a[4] * a[2] * a[9] +
            a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
  double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
  Mat4 r;
  if (det == 0.0 || !std::isfinite(det)) return r;
  double inv_det = 1.0 / det;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r.m[c][row] = static_cast<float>(inv[c * 4 + row] * inv_det);
  return r;
}

Mat4 Mat4::transpose() const {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r.m[c][row] = m[row][c];
  return r;
}

}  // namespace gib
