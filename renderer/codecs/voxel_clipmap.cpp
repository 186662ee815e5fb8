#include "renderer/codecs/voxel_clipmap.h"

#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"

#include <algorithm>
#include <cmath>

namespace gib::codecs {
namespace {

int32_t wrap1(int32_t g, int32_t n) { return ((g % n) + n) % n; }
Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Float3 cross(Float3 a, Float3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
float dot(Float3 a, Float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool separated(Float3 axis, Float3 v0, Float3 v1, Float3 v2, Float3 h) {
  const float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
  const float r = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
  return std::min(p0, std::min(p1, p2)) > r || std::max(p0, std::max(p1, p2)) < -r;
}

}  // namespace

Int3 vc_wrap(Int3 g, int32_t n) { return {wrap1(g.x, n), wrap1(g.y, n), wrap1(g.z, n)}; }
uint32_t vc_slot_index(Int3 s, int32_t n) { return uint32_t((s.z * n + s.y) * n + s.x); }
Int3 vc_slot_world(Int3 s, Int3 o, int32_t n) {
  const Int3 d = vc_wrap({s.x - o.x, s.y - o.y, s.z - o.z}, n);
  return {o.x + d.x, o.y + d.y, o.z + d.z};
}
bool vc_in_box(Int3 g, Int3 o, int32_t n) {
  return g.x >= o.x && g.y >= o.y && g.z >= o.z && g.x < o.x + n && g.y < o.y + n && g.z < o.z + n;
}
uint32_t vc_voxel_index(uint32_t level, Int3 g, int32_t n) {
  return level * uint32_t(n * n * n) + vc_slot_index(vc_wrap(g, n), n);
}
Int3 vc_origin_around(Float3 x, float size, int32_t n) {
  return {int32_t(std::floor(x.x / size)) - n / 2, int32_t(std::floor(x.y / size)) - n / 2,
          int32_t(std::floor(x.z / size)) - n / 2};
}
uint32_t vc_voxel_level(Float3 x, const Int3* origins, uint32_t levels, float voxel_size, int32_t n) {
  for (uint32_t l = 0; l < levels; ++l) {
    const float s = voxel_size * float(1u << l);
    const Int3 g{int32_t(std::floor(x.x / s)), int32_t(std::floor(x.y / s)), int32_t(std::floor(x.z / s))};
    if (vc_in_box(g, origins[l], n)) return l;
  }
  return levels;
}

CubeValue vc_cube_eval(const AmbientAxis& x, const AmbientAxis& y, const AmbientAxis& z, Float3 n) {
  const AmbientAxis* axes[3] = {&x, &y, &z};
  const float c[3] = {n.x, n.y, n.z};
  CubeValue v;
  float* b[3] = {&v.bounce.x, &v.bounce.y, &v.bounce.z};
  float* s[3] = {&v.sky.x, &v.sky.y, &v.sky.z};
  for (int a = 0; a < 3; ++a) {
    const float w = c[a] * c[a];
    const size_t o = c[a] >= 0.0f ? 0 : 3;
    for (int ch = 0; ch < 3; ++ch) {
      *b[ch] += w * (*axes[a])[o + ch];
      *s[ch] += w * (*axes[a])[o + 6 + ch];
    }
    v.hit += w * (*axes[a])[c[a] >= 0.0f ? 12 : 13];
  }
  return v;
}

uint32_t vc_opacity_byte(float opacity) {
  return uint32_t(std::clamp(std::floor(opacity * 255.0f + 0.5f), 1.0f, 255.0f));
}

bool vc_triangle_box_overlap(Float3 a, Float3 b, Float3 c, Float3 centre, Float3 h) {
  const Float3 v0 = sub(a, centre), v1 = sub(b, centre), v2 = sub(c, centre);
  const float lo[3] = {std::min(v0.x, std::min(v1.x, v2.x)), std::min(v0.y, std::min(v1.y, v2.y)),
                       std::min(v0.z, std::min(v1.z, v2.z))};
  const float hi[3] = {std::max(v0.x, std::max(v1.x, v2.x)), std::max(v0.y, std::max(v1.y, v2.y)),
                       std::max(v0.z, std::max(v1.z, v2.z))};
  const float he[3] = {h.x, h.y, h.z};
  for (int i = 0; i < 3; ++i)
    if (lo[i] > he[i] || hi[i] < -he[i]) return false;
  const Float3 e0 = sub(v1, v0), e1 = sub(v2, v1), e2 = sub(v0, v2);
  if (separated(cross(e0, e1), v0, v1, v2, h)) return false;
  const Float3 units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Float3& u : units)
    if (separated(cross(u, e0), v0, v1, v2, h) || separated(cross(u, e1), v0, v1, v2, h) ||
        separated(cross(u, e2), v0, v1, v2, h))
      return false;
  return true;
}

uint32_t vc_fill_key(uint32_t op8, bool facing, uint32_t triangle) {
  const uint32_t mask = 0x7fffffu;
  const uint32_t id = triangle < mask ? triangle + 1u : 0u;
  return (op8 << 24) | (facing ? 0x800000u : 0u) | id;
}

uint32_t vc_second_triangle(uint32_t y, uint32_t w) {
  return (y >> 13) | (((w & 0x7800000u) >> 23) << 19);
}

void vc_set_second_triangle(uint32_t& y, uint32_t& w, uint32_t id) {
  y = (y & 0x1fffu) | (id << 13);
  w = (w & ~0x7800000u) | (((id >> 19) << 23) & 0x7800000u);
}

uint32_t vc_vis_row_step(uint32_t free_row, uint32_t seed, uint32_t row, uint32_t beside, uint32_t xlo, uint32_t xhi) {
  const uint32_t all = (1u << uint32_t(glsl::kVcVisWindow)) - 1u;
  const uint32_t up = all & ~((2u << xhi) - 1u), down = (1u << xlo) - 1u;
  uint32_t r = seed | (free_row & (row | beside));
  for (int i = 0; i < glsl::kVcVisWindow - 1; ++i) r |= free_row & (((r << 1u) & up) | ((r >> 1u) & down));
  return r & all;
}

VisRows vc_vis_flood(const VisRows& free_rows, Int3 lo, Int3 hi) {
  constexpr int w = glsl::kVcVisWindow;
  static_assert(w * w == 64, "VisRows holds the flood window's rows");
  VisRows seeds{};
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) seeds[z * w + y] |= 1u << x;
  VisRows cur = seeds, next{};
  for (uint32_t step = 0; step < glsl::kVcVisSteps; ++step) {
    for (int r = 0; r < w * w; ++r) {
      const int y = r % w, z = r / w;
      const uint32_t beside = (y > hi.y ? cur[r - 1] : 0u) | (y < lo.y ? cur[r + 1] : 0u) |
                              (z > hi.z ? cur[r - w] : 0u) | (z < lo.z ? cur[r + w] : 0u);
      next[r] = vc_vis_row_step(free_rows[r], seeds[r], cur[r], beside, uint32_t(lo.x), uint32_t(hi.x));
    }
    cur = next;
  }
  return cur;
}

std::array<uint32_t, 7> vc_vis_pack(const VisRows& reached) {
  constexpr int w = glsl::kVcVisWindow, span = glsl::kVcVisSpan;
  static_assert(glsl::kVcCellVisWords == 7 && span * span * span <= 7 * 32, "mask words");
  std::array<uint32_t, 7> words{};
  for (int bit = 0; bit < span * span * span; ++bit) {
    const int x = bit % span + 1, y = (bit / span) % span + 1, z = bit / (span * span) + 1;
    words[bit / 32] |= ((reached[z * w + y] >> x) & 1u) << (bit % 32);
  }
  return words;
}

int32_t vc_vis_bit(Int3 g, Int3 k) {
  const Int3 c{g.x - (2 * k.x - 2), g.y - (2 * k.y - 2), g.z - (2 * k.z - 2)};
  const int span = glsl::kVcVisSpan;
  if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= span || c.y >= span || c.z >= span) return -1;
  return (c.z * span + c.y) * span + c.x;
}

Bary vc_closest_on_triangle(Float3 p, Float3 a, Float3 b, Float3 c) {
  const Float3 e1 = sub(b, a), e2 = sub(c, a), q = sub(p, a);
  const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  const float det = d11 * d22 - d12 * d12;
  if (!(det > 1e-20f * d11 * d22) || d11 <= 0.0f || d22 <= 0.0f) return {};
  const float q1 = dot(q, e1), q2 = dot(q, e2);
  const Bary inside{(d22 * q1 - d12 * q2) / det, (d11 * q2 - d12 * q1) / det};
  if (inside.u >= 0.0f && inside.v >= 0.0f && inside.u + inside.v <= 1.0f) return inside;
  // The nearest point of each edge (a-b, a-c, b-c), then the nearest of the three.
  const float tab = std::clamp(q1 / d11, 0.0f, 1.0f), tac = std::clamp(q2 / d22, 0.0f, 1.0f);
  const Float3 ebc = sub(c, b);
  const float tbc = std::clamp(dot(sub(p, b), ebc) / std::max(dot(ebc, ebc), 1e-30f), 0.0f, 1.0f);
  const Bary cand[3] = {{tab, 0.0f}, {0.0f, tac}, {1.0f - tbc, tbc}};
  Bary best = cand[0];
  float best_d = 3.4e38f;
  for (const Bary& k : cand) {
    const Float3 x{a.x + e1.x * k.u + e2.x * k.v - p.x, a.y + e1.y * k.u + e2.y * k.v - p.y,
                   a.z + e1.z * k.u + e2.z * k.v - p.z};
    const float d = dot(x, x);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}

}  // namespace gib::codecs
