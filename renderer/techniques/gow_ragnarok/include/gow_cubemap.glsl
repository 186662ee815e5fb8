// The reflection cube map's addressing and the parallax correction of "Raytraced Cubemaps"
// (gow_ragnarok.md, "Reflections"). Six faces of N x N texels side by side in one 6N x N image,
// face = 2 x axis + (negative ? 1 : 0). On the face of axis a (x, y or z), the other two axes
// (b, c) = (y, z), (z, x) or (x, y) in that order, and st = (d_b, d_c) / |d_a| in [-1, 1].
// Box projection (Lagarde and Zanuttini 2012): a reflection ray from x, inside the proxy box,
// leaves the box at x + t d; the cube map, captured at `capture`, is read in the direction from
// the capture point to that exit point. CPU mirror: gow_ragnarok/gow_cubemap.h.
#ifndef GOW_CUBEMAP_GLSL
#define GOW_CUBEMAP_GLSL

// Direction (not normalised) through st in [-1, 1]^2 of a face.
vec3 gow_cube_dir(uint face, vec2 st) {
  uint axis = face >> 1u;
  float s = (face & 1u) != 0u ? -1.0 : 1.0;
  if (axis == 0u) return vec3(s, st.x, st.y);
  if (axis == 1u) return vec3(st.y, s, st.x);
  return vec3(st.x, st.y, s);
}

// The face of d and its st, the inverse of gow_cube_dir for d != 0.
uint gow_cube_face(vec3 d, out vec2 st) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) {
    st = d.yz / a.x;
    return d.x < 0.0 ? 1u : 0u;
  }
  if (a.y >= a.z) {
    st = d.zx / a.y;
    return d.y < 0.0 ? 3u : 2u;
  }
  st = d.xy / a.z;
  return d.z < 0.0 ? 5u : 4u;
}

// The texel of the 6N x N image that direction d falls in.
ivec2 gow_cube_texel(vec3 d, uint n) {
  vec2 st;
  uint face = gow_cube_face(d, st);
  ivec2 t = clamp(ivec2((st * 0.5 + 0.5) * float(n)), ivec2(0), ivec2(int(n) - 1));
  return ivec2(int(face * n) + t.x, t.y);
}

// Distance along d from x (inside the box) to the box's far side; 0 where x is outside.
float gow_box_exit(vec3 x, vec3 d, vec3 bmin, vec3 bmax) {
  vec3 inv = 1.0 / d;  // +-inf on an axis d does not move along: that axis never limits
  vec3 t = max((bmin - x) * inv, (bmax - x) * inv);
  return max(min(t.x, min(t.y, t.z)), 0.0);
}

// The parallax-corrected look-up direction.
vec3 gow_box_project(vec3 x, vec3 d, vec3 bmin, vec3 bmax, vec3 capture) {
  return x + d * gow_box_exit(x, d, bmin, bmax) - capture;
}
#endif
