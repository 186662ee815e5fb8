// Image textures: fetch and filter from the packed texture buffer (gib_textures, declared by
// GIB_SCENE_BUFFERS). Layout and CPU mirror: renderer/scene/texture.h (same operation order,
// arithmetic marked precise, decode through the buffer's own tables: GPU and CPU agree bit for
// bit, tests/test_textures_gpu.cpp).
//
//   gib_texture_texel(t, level, xy)          one texel, wrapped, decoded to linear
//   gib_texture_bilinear(t, level, uv)       bilinear within a level (clamped to the chain)
//   gib_texture_level(t, duv_dx, duv_dy)     the level nearest log2 of the pixel footprint
//   gib_texture_sample(t, uv, duv_dx, duv_dy) the two together
#ifndef GIB_TEXTURES_GLSL
#define GIB_TEXTURES_GLSL

#define GIB_TEXTURE_NO_INDEX 0xffffffffu
#define GIB_TEXTURE_TABLE_WORD 513u

uvec4 gib_texture_descriptor(uint t) {
  uint b = GIB_TEXTURE_TABLE_WORD + 4u * t;
  return uvec4(gib_textures[b], gib_textures[b + 1u], gib_textures[b + 2u], gib_textures[b + 3u]);
}

int gib_texture_wrap(int i, uint n) {
  int r = i % int(n);
  return r < 0 ? r + int(n) : r;
}

vec4 gib_texture_texel(uint t, uint level, ivec2 xy) {
  uvec4 d = gib_texture_descriptor(t);
  level = min(level, (d.z & 0x7fffffffu) - 1u);
  uint offset = d.w, w = d.x, h = d.y;
  for (uint l = 0u; l < level; ++l) {
    offset += w * h;
    w = max(1u, w / 2u);
    h = max(1u, h / 2u);
  }
  uint c = gib_textures[offset + uint(gib_texture_wrap(xy.y, h)) * w + uint(gib_texture_wrap(xy.x, w))];
  uint table = (d.z >> 31) != 0u ? 0u : 256u;
  return vec4(uintBitsToFloat(gib_textures[table + (c & 0xffu)]),
              uintBitsToFloat(gib_textures[table + ((c >> 8) & 0xffu)]),
              uintBitsToFloat(gib_textures[table + ((c >> 16) & 0xffu)]),
              uintBitsToFloat(gib_textures[256u + (c >> 24)]));
}

float gib_texture_wrap01(float u) {
  precise float f = u - floor(u);
  return (f >= 0.0 && f < 1.0) ? f : 0.0;
}

vec4 gib_texture_bilinear(uint t, uint level, vec2 uv) {
  uvec4 d = gib_texture_descriptor(t);
  level = min(level, (d.z & 0x7fffffffu) - 1u);
  uint w = max(1u, d.x >> level), h = max(1u, d.y >> level);
  precise float x = gib_texture_wrap01(uv.x) * float(w) - 0.5;
  precise float y = gib_texture_wrap01(uv.y) * float(h) - 0.5;
  precise float x0 = floor(x);
  precise float y0 = floor(y);
  precise float fx = x - x0;
  precise float fy = y - y0;
  ivec2 i = ivec2(int(x0), int(y0));
  vec4 c00 = gib_texture_texel(t, level, i);
  vec4 c10 = gib_texture_texel(t, level, i + ivec2(1, 0));
  vec4 c01 = gib_texture_texel(t, level, i + ivec2(0, 1));
  vec4 c11 = gib_texture_texel(t, level, i + ivec2(1, 1));
  precise vec4 r0 = c00 + (c10 - c00) * fx;
  precise vec4 r1 = c01 + (c11 - c01) * fx;
  precise vec4 r = r0 + (r1 - r0) * fy;
  return r;
}

uint gib_texture_level(uint t, vec2 duv_dx, vec2 duv_dy) {
  uvec4 d = gib_texture_descriptor(t);
  uint mips = d.z & 0x7fffffffu;
  precise float ax = duv_dx.x * float(d.x);
  precise float ay = duv_dx.y * float(d.y);
  precise float bx = duv_dy.x * float(d.x);
  precise float by = duv_dy.y * float(d.y);
  precise float rho2 = max(ax * ax + ay * ay, bx * bx + by * by);
  uint level = 0u;
  float bound = 2.0;
  while (level + 1u < mips && rho2 >= bound) {
    ++level;
    bound *= 4.0;
  }
  return level;
}

vec4 gib_texture_sample(uint t, vec2 uv, vec2 duv_dx, vec2 duv_dy) {
  return gib_texture_bilinear(t, gib_texture_level(t, duv_dx, duv_dy), uv);
}

#endif  // GIB_TEXTURES_GLSL
