// Triangle / box overlap by the separating axis theorem (Akenine-Moller 2001: the box's three
// axes, the triangle's normal, and the nine cross products of box axes and triangle edges).
// Touching counts as overlapping, so a wall on a voxel boundary fills the voxels on both sides.
// CPU mirror: codecs::vc_triangle_box_overlap, vc_fill_key, vc_closest_on_triangle
// (renderer/codecs/voxel_clipmap.h).
#ifndef GIB_VC_VOXELIZE_GLSL
#define GIB_VC_VOXELIZE_GLSL

bool vc_separated(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 h) {
  float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
  float r = dot(h, abs(axis));
  return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

// Triangle a, b, c against the box of centre `centre` and half extent h.
bool vc_triangle_box_overlap(vec3 a, vec3 b, vec3 c, vec3 centre, vec3 h) {
  vec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;
  if (any(greaterThan(min(v0, min(v1, v2)), h)) || any(lessThan(max(v0, max(v1, v2)), -h))) return false;
  vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
  if (vc_separated(cross(e0, e1), v0, v1, v2, h)) return false;
  for (int i = 0; i < 3; ++i) {
    vec3 u = vec3(i == 0 ? 1.0 : 0.0, i == 1 ? 1.0 : 0.0, i == 2 ? 1.0 : 0.0);
    if (vc_separated(cross(u, e0), v0, v1, v2, h) || vc_separated(cross(u, e1), v0, v1, v2, h) ||
        vc_separated(cross(u, e2), v0, v1, v2, h))
      return false;
  }
  return true;
}

// scene_voxel_fill's key for a triangle overlapping a voxel (layout: voxel_clipmap_shared.h).
uint vc_fill_key(uint op8, bool facing, uint triangle) {
  uint id = triangle < kVcFillTriangleMask ? triangle + 1u : 0u;
  return (op8 << 24) | (facing ? kVcFillFacing : 0u) | id;
}

// Barycentrics (u, v) of the point of triangle a, b, c nearest p (the point: a (1 - u - v) +
// b u + c v): p's projection on the plane when it falls inside, else the nearest point of the
// nearest edge. A degenerate triangle gives a.
vec2 vc_closest_on_triangle(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 e1 = b - a, e2 = c - a, q = p - a;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  float det = d11 * d22 - d12 * d12;
  if (!(det > 1e-20 * d11 * d22) || d11 <= 0.0 || d22 <= 0.0) return vec2(0.0);
  float q1 = dot(q, e1), q2 = dot(q, e2);
  vec2 uv = vec2(d22 * q1 - d12 * q2, d11 * q2 - d12 * q1) / det;
  if (uv.x >= 0.0 && uv.y >= 0.0 && uv.x + uv.y <= 1.0) return uv;
  // Edges a-b (v = 0), a-c (u = 0), b-c (u + v = 1): each point at its clamped parameter.
  float tab = clamp(q1 / d11, 0.0, 1.0), tac = clamp(q2 / d22, 0.0, 1.0);
  vec3 ebc = c - b;
  float tbc = clamp(dot(p - b, ebc) / max(dot(ebc, ebc), 1e-30), 0.0, 1.0);
  vec2 cand[3] = vec2[3](vec2(tab, 0.0), vec2(0.0, tac), vec2(1.0 - tbc, tbc));
  vec2 best = cand[0];
  float best_d = 3.4e38;
  for (int i = 0; i < 3; ++i) {
    vec3 x = a + e1 * cand[i].x + e2 * cand[i].y - p;
    float d = dot(x, x);
    if (d < best_d) {
      best_d = d;
      best = cand[i];
    }
  }
  return best;
}
#endif
