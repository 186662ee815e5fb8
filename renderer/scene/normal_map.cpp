#include "renderer/scene/fp_contract_off.h"  // first: the mirror rounds like the shader's `precise`

#include "renderer/scene/normal_map.h"

#include <cmath>

namespace gib {
namespace {

bool finite(float x) { return std::isfinite(x); }

}  // namespace

Vec3 apply_normal_map(Vec3 n, const Vec3 p[3], const Vec2 t[3], Vec3 texel, float scale) {
  const Vec3 e1{p[1].x - p[0].x, p[1].y - p[0].y, p[1].z - p[0].z};
  const Vec3 e2{p[2].x - p[0].x, p[2].y - p[0].y, p[2].z - p[0].z};
  const Vec2 d1{t[1].x - t[0].x, t[1].y - t[0].y};
  const Vec2 d2{t[2].x - t[0].x, t[2].y - t[0].y};
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::fabs(det) > 0.0f) || !finite(det)) return n;
  Vec3 tu{e1.x * d2.y - e2.x * d1.y, e1.y * d2.y - e2.y * d1.y, e1.z * d2.y - e2.z * d1.y};
  Vec3 tv{e2.x * d1.x - e1.x * d2.x, e2.y * d1.x - e1.y * d2.x, e2.z * d1.x - e1.z * d2.x};
  if (det < 0.0f) {
    tu = {-tu.x, -tu.y, -tu.z};
    tv = {-tv.x, -tv.y, -tv.z};
  }
  const float tn = tu.x * n.x + tu.y * n.y + tu.z * n.z;
  Vec3 tt{tu.x - n.x * tn, tu.y - n.y * tn, tu.z - n.z * tn};
  const float tl2 = tt.x * tt.x + tt.y * tt.y + tt.z * tt.z;
  if (!(tl2 > 0.0f) || !finite(tl2)) return n;
  const float ti = 1.0f / std::sqrt(tl2);
  tt = {tt.x * ti, tt.y * ti, tt.z * ti};
  Vec3 b{n.y * tt.z - n.z * tt.y, n.z * tt.x - n.x * tt.z, n.x * tt.y - n.y * tt.x};
  const float along_v = b.x * tv.x + b.y * tv.y + b.z * tv.z;
  if (along_v > 0.0f) b = {-b.x, -b.y, -b.z};
  const Vec3 m{(texel.x * 2.0f - 1.0f) * scale, (texel.y * 2.0f - 1.0f) * scale, texel.z * 2.0f - 1.0f};
  const Vec3 r{tt.x * m.x + b.x * m.y + n.x * m.z, tt.y * m.x + b.y * m.y + n.y * m.z,
               tt.z * m.x + b.z * m.y + n.z * m.z};
  const float rl2 = r.x * r.x + r.y * r.y + r.z * r.z;
  if (!(rl2 > 0.0f) || !finite(rl2)) return n;
  const float ri = 1.0f / std::sqrt(rl2);
  return {r.x * ri, r.y * ri, r.z * ri};
}

Vec3 encode_tangent_normal(Vec3 m) { return {(m.x + 1.0f) * 0.5f, (m.y + 1.0f) * 0.5f, (m.z + 1.0f) * 0.5f}; }

}  // namespace gib
