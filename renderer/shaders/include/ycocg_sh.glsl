// YCoCg spherical-harmonic radiance in 64 bits (owner: codecs). CPU mirror and the full
// description: renderer/codecs/ycocg_sh.h (bit for bit).
//   uvec2 gib_pack_ycocg_sh(float y0, vec3 y1, vec2 cocg)
//   void gib_unpack_ycocg_sh(uvec2 w, out float y0, out vec3 y1, out vec2 cocg)
//   vec3 gib_rgb_to_ycocg(vec3 rgb); vec3 gib_ycocg_to_rgb(vec3 ycocg)
#ifndef GIB_YCOCG_SH_GLSL
#define GIB_YCOCG_SH_GLSL

bool gib_ycocg_finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }

uint gib_ycocg_quantise(float scaled, bool is_unsigned) {
  if (is_unsigned) {
    precise float x = min(max(scaled, 0.0), 1.0) * 255.0;
    precise float r = x + 0.5;
    return uint(floor(r));
  }
  precise float x = min(max(scaled, -1.0), 1.0) * 127.0;
  precise float r = x + 0.5;
  return uint(int(floor(r)) + 127);
}

uvec2 gib_pack_ycocg_sh(float y0, vec3 y1, vec2 cocg) {
  float v[6] = float[6](y0, y1.x, y1.y, y1.z, cocg.x, cocg.y);
  float m = 0.0;
  for (int i = 0; i < 6; ++i) {
    if (!gib_ycocg_finite(v[i])) v[i] = 0.0;
    m = max(m, abs(v[i]));
  }
  v[0] = max(v[0], 0.0);
  if (m < 7.888609052210118e-31) return uvec2(127u << 8u | 127u << 16u | 127u << 24u, 127u | 127u << 8u | 28u << 16u);
  uint b = floatBitsToUint(m);
  int e = int((b >> 23u) & 255u) - 127;
  if ((b & 0x7fffffu) != 0u) ++e;
  e = min(e, 127);
  uint q[6];
  for (int i = 0; i < 6; ++i) q[i] = gib_ycocg_quantise(ldexp(v[i], -e), i == 0);
  return uvec2(q[0] | q[1] << 8u | q[2] << 16u | q[3] << 24u, q[4] | q[5] << 8u | uint(e + 128) << 16u);
}

void gib_unpack_ycocg_sh(uvec2 w, out float y0, out vec3 y1, out vec2 cocg) {
  int e = int((w.y >> 16u) & 0xffffu) - 128;
  precise float a = float(w.x & 255u) * (1.0 / 255.0);
  y0 = ldexp(a, e);
  precise vec3 b = vec3(ivec3((w.x >> 8u) & 255u, (w.x >> 16u) & 255u, w.x >> 24u) - 127) * (1.0 / 127.0);
  y1 = vec3(ldexp(b.x, e), ldexp(b.y, e), ldexp(b.z, e));
  precise vec2 c = vec2(ivec2(w.y & 255u, (w.y >> 8u) & 255u) - 127) * (1.0 / 127.0);
  cocg = vec2(ldexp(c.x, e), ldexp(c.y, e));
}

vec3 gib_rgb_to_ycocg(vec3 c) {
  return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 gib_ycocg_to_rgb(vec3 v) { return vec3(v.x + v.y - v.z, v.x + v.z, v.x - v.y - v.z); }

#endif  // GIB_YCOCG_SH_GLSL
