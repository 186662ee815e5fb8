#include "renderer/codecs/octahedral.h"

#include <cmath>

namespace gib::codecs {

namespace {
float sign_not_zero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }
}  // namespace

Vec2 oct_encode(Vec3 n) {
  const float l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
  float px = n.x / l1, py = n.y / l1;
  if (n.z < 0.0f) {
    const float fx = (1.0f - std::fabs(py)) * sign_not_zero(px);
    const float fy = (1.0f - std::fabs(px)) * sign_not_zero(py);
    px = fx;
    py = fy;
  }
  return {px * 0.5f + 0.5f, py * 0.5f + 0.5f};
}

Vec3 oct_decode(Vec2 uv) {
  const float px = uv.x * 2.0f - 1.0f, py = uv.y * 2.0f - 1.0f;
  Vec3 n{px, py, 1.0f - std::fabs(px) - std::fabs(py)};
  const float t = std::fmax(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}

Texel oct_border_source(Texel t, int n) {
  const int last = n + 1;
  const bool left = t.x == 0, right = t.x == last, top = t.y == 0, bottom = t.y == last;
  if ((left || right) && (top || bottom)) return {left ? n : 1, top ? n : 1};  // corners
  if (left || right) return {left ? 1 : n, last - t.y};
  if (top || bottom) return {last - t.x, top ? 1 : n};
  return t;
}

Vec2 oct_tile_coord(Vec3 dir, int n) {
  const Vec2 uv = oct_encode(dir);
  return {1.0f + uv.x * float(n), 1.0f + uv.y * float(n)};
}

Vec3 oct_texel_direction(Texel t, int n) {
  return oct_decode({(float(t.x - 1) + 0.5f) / float(n), (float(t.y - 1) + 0.5f) / float(n)});
}

}  // namespace gib::codecs
