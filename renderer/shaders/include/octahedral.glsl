// Octahedral mapping and bordered octahedral tiles (owner: codecs). CPU mirror and the full
// description: renderer/codecs/octahedral.h.
//   vec2 gib_oct_encode(vec3 n)      unit (or any non-zero) vector -> [0,1]^2; +z at the centre,
//                                    the lower hemisphere folded into the corners
//   vec3 gib_oct_decode(vec2 uv)     [0,1]^2 -> unit vector
//   ivec2 gib_oct_border_source(ivec2 texel, int interior)
//       tile-local texel (0..interior+1 per axis, 0 and interior+1 the border) -> the
//       tile-local interior texel whose value it copies (itself for interior texels): edges
//       mirror about their midpoint, corners take the opposite interior corner.
//   vec2 gib_oct_tile_coord(vec3 n, int interior)   continuous tile-local texel coordinate
//       (texel centres at integer + 0.5) for bilinear sampling: 1 + uv * interior
//   vec3 gib_oct_texel_direction(ivec2 texel, int interior)  direction at an interior texel centre
#ifndef GIB_OCTAHEDRAL_GLSL
#define GIB_OCTAHEDRAL_GLSL

vec2 gib_oct_sign_not_zero(vec2 v) {
  return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
}

vec2 gib_oct_encode(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * gib_oct_sign_not_zero(p);
  return p * 0.5 + 0.5;
}

vec3 gib_oct_decode(vec2 uv) {
  vec2 p = uv * 2.0 - 1.0;
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  float t = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return normalize(n);
}

ivec2 gib_oct_border_source(ivec2 texel, int interior) {
  int last = interior + 1;
  bool left = texel.x == 0, right = texel.x == last;
  bool top = texel.y == 0, bottom = texel.y == last;
  if ((left || right) && (top || bottom)) return ivec2(left ? interior : 1, top ? interior : 1);
  if (left || right) return ivec2(left ? 1 : interior, last - texel.y);
  if (top || bottom) return ivec2(last - texel.x, top ? 1 : interior);
  return texel;
}

vec2 gib_oct_tile_coord(vec3 n, int interior) { return 1.0 + gib_oct_encode(n) * float(interior); }

vec3 gib_oct_texel_direction(ivec2 texel, int interior) {
  return gib_oct_decode((vec2(texel - 1) + 0.5) / float(interior));
}

#endif  // GIB_OCTAHEDRAL_GLSL
