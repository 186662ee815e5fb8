// Triangle / box overlap by the separating axis theorem (Akenine-Moller 2001: the box's three
// axes, the triangle's normal, and the nine cross products of box axes and triangle edges).
// Touching counts as overlapping, so a wall on a voxel boundary fills the voxels on both sides.
// CPU mirror: codecs::vc_triangle_box_overlap (renderer/codecs/voxel_clipmap.h).
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
#endif
