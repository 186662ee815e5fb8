// Tangent-space normal maps (glTF normalTexture). CPU mirror: renderer/scene/normal_map.h (same
// operation order, arithmetic marked precise; tests/test_normal_map_gpu.cpp checks they agree).
//
// The tangent frame is the triangle's own, from its positions and uvs (glTF's TANGENT attribute
// is not read): T along increasing u, made orthogonal to the shading normal n, and B = w *
// cross(n, T), w = +1 when cross(n, T) points along decreasing v, as glTF's convention has it
// (texture origin at the top left, the map's +Y up in the image), -1 for a mirrored mapping.
// That is MikkTSpace's frame wherever a triangle's tangent is constant (planar, uniformly mapped
// faces); along smoothed seams MikkTSpace averages per vertex and this does not.
//
//   gib_normal_map(n, p0, p1, p2, t0, t1, t2, texel, scale)
//     n: unit shading normal; texel: the map's linear rgb in [0, 1]; scale: normalTexture.scale.
//     Returns normalize(T m.x + B m.y + n m.z), m = (2 texel - 1) * (scale, scale, 1); n itself
//     where the uvs are degenerate or the result is not a finite unit vector.
#ifndef GIB_NORMAL_MAP_GLSL
#define GIB_NORMAL_MAP_GLSL
#include "finite.glsl"

vec3 gib_normal_map(vec3 n, vec3 p0, vec3 p1, vec3 p2, vec2 t0, vec2 t1, vec2 t2, vec3 texel, float scale) {
  precise vec3 e1 = p1 - p0;
  precise vec3 e2 = p2 - p0;
  precise vec2 d1 = t1 - t0;
  precise vec2 d2 = t2 - t0;
  precise float det = d1.x * d2.y - d2.x * d1.y;
  if (!(abs(det) > 0.0) || !gib_finite(det)) return n;
  // det * dp/du and det * dp/dv.
  precise vec3 tu = e1 * d2.y - e2 * d1.y;
  precise vec3 tv = e2 * d1.x - e1 * d2.x;
  if (det < 0.0) {
    tu = -tu;
    tv = -tv;
  }
  precise float tn = tu.x * n.x + tu.y * n.y + tu.z * n.z;
  precise vec3 t = tu - n * tn;
  precise float tl2 = t.x * t.x + t.y * t.y + t.z * t.z;
  if (!(tl2 > 0.0) || !gib_finite(tl2)) return n;
  t = t * (1.0 / sqrt(tl2));
  precise vec3 b = vec3(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x);
  precise float along_v = b.x * tv.x + b.y * tv.y + b.z * tv.z;
  if (along_v > 0.0) b = -b;  // cross(n, t) runs along increasing v: a mirrored mapping
  precise vec3 m = texel * 2.0 - 1.0;
  m.x = m.x * scale;
  m.y = m.y * scale;
  precise vec3 r = t * m.x + b * m.y + n * m.z;
  precise float rl2 = r.x * r.x + r.y * r.y + r.z * r.z;
  if (!(rl2 > 0.0) || !gib_finite(rl2)) return n;
  return r * (1.0 / sqrt(rl2));
}

#endif
