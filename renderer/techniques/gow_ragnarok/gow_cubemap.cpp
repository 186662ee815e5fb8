#include "renderer/techniques/gow_ragnarok/gow_cubemap.h"

#include <algorithm>
#include <cmath>

namespace gib {

Vec3 gow_cube_dir(uint32_t face, float s, float t) {
  const uint32_t axis = face >> 1u;
  const float sign = (face & 1u) != 0u ? -1.0f : 1.0f;
  if (axis == 0) return {sign, s, t};
  if (axis == 1) return {t, sign, s};
  return {s, t, sign};
}

uint32_t gow_cube_face(Vec3 d, float& s, float& t) {
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  if (ax >= ay && ax >= az) {
    s = d.y / ax, t = d.z / ax;
    return d.x < 0 ? 1 : 0;
  }
  if (ay >= az) {
    s = d.z / ay, t = d.x / ay;
    return d.y < 0 ? 3 : 2;
  }
  s = d.x / az, t = d.y / az;
  return d.z < 0 ? 5 : 4;
}

void gow_cube_texel(Vec3 d, uint32_t n, int32_t& x, int32_t& y) {
  float s, t;
  const uint32_t face = gow_cube_face(d, s, t);
  const int32_t last = int32_t(n) - 1;
  x = int32_t(face * n) + std::clamp(int32_t((s * 0.5f + 0.5f) * float(n)), 0, last);
  y = std::clamp(int32_t((t * 0.5f + 0.5f) * float(n)), 0, last);
}

float gow_box_exit(Vec3 x, Vec3 d, Vec3 bmin, Vec3 bmax) {
  float best = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / d[a];
    best = std::fmin(best, std::fmax((bmin[a] - x[a]) * inv, (bmax[a] - x[a]) * inv));
  }
  return std::fmax(best, 0.0f);
}

Vec3 gow_box_project(Vec3 x, Vec3 d, Vec3 bmin, Vec3 bmax, Vec3 capture) {
  return x + d * gow_box_exit(x, d, bmin, bmax) - capture;
}

}  // namespace gib
