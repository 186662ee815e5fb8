// Small vector/matrix types for the CPU side (column-major Mat4, like GLSL).
#pragma once
#include <cmath>
#include <cstdint>

namespace gib {

struct Vec2 { float x = 0, y = 0; };

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  friend constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
  friend constexpr Vec3 operator*(float s, Vec3 a) { return a * s; }
  friend constexpr Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
  friend constexpr Vec3 operator/(Vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
  Vec3& operator+=(Vec3 b) { x += b.x; y += b.y; z += b.z; return *this; }
  friend constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};
constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) {
  float l = length(a);
  return l > 0 ? a / l : Vec3{0, 0, 0};
}
inline Vec3 vmin(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline Vec3 vmax(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }

struct Vec4 { float x = 0, y = 0, z = 0, w = 0; };

// Column-major: m[col][row]; transform_point multiplies M * (p, 1).
struct Mat4 {
  float m[4][4] = {};
  static Mat4 identity() {
    Mat4 r;
    for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0f;
    return r;
  }
  static Mat4 translation(Vec3 t) {
    Mat4 r = identity();
    r.m[3][0] = t.x; r.m[3][1] = t.y; r.m[3][2] = t.z;
    return r;
  }
  static Mat4 scaling(Vec3 s) {
    Mat4 r = identity();
    r.m[0][0] = s.x; r.m[1][1] = s.y; r.m[2][2] = s.z;
    return r;
  }
  static Mat4 rotation_x(float rad);
  static Mat4 rotation_y(float rad);
  static Mat4 rotation_z(float rad);
  // T * Rx * Ry * Rz * S
  static Mat4 trs(Vec3 t, Vec3 rotation_deg, Vec3 s);
  static Mat4 look_at(Vec3 eye, Vec3 target, Vec3 up);  // view matrix (right-handed, -Z forward)
  static Mat4 perspective(float fov_y_rad, float aspect, float near_plane, float far_plane);  // Vulkan clip (y down, z 0..1)
  friend Mat4 operator*(const Mat4& a, const Mat4& b);
  Vec3 transform_point(Vec3 p) const;
  Vec3 transform_vector(Vec3 v) const;
  Vec4 transform(Vec4 v) const;
  Mat4 inverse() const;   // general 4x4 inverse
  Mat4 transpose() const;
};

}  // namespace gib
