// Procedural material textures and alpha masks. CPU mirror: renderer/scene/material_eval.h
// (same hash, same formulas, same operation order; arithmetic marked precise so it rounds like
// the CPU).
//
//   gib_material_albedo(m, uv)       texture none: albedo; checker: albedo / albedo2 in
//                                    alternating cells of size 1/texture_scale; value_noise:
//                                    albedo -> albedo2 by a hash-based value noise at
//                                    texture_scale lattice cells per uv unit.
//   gib_material_albedo_filtered(m, uv, duv_dx, duv_dy)
//                                    the albedo averaged over 4x4 samples of the pixel footprint.
//   gib_material_alpha(m, uv, seed)  coverage in [0, 1]: alpha none: 1; leaf_mask: 1 inside a
//                                    leaf-shaped ellipse in uv [0,1]^2, 0 outside; checker_mask:
//                                    1 / 0 in alternating checker cells; opacity: m.opacity.
//                                    seed is unused by these kinds (kept so stochastic masks need
//                                    no new signature).
//   Image textures (TextureKind image, AlphaKind texture_mask / texture_opacity, emissive
//   textures: renderer/scene/texture.h) are sampled bilinearly from mip level 0 by the unfiltered
//   functions (traced rays) and at the footprint's level by the _filtered ones (G-buffers); the
//   base colour and emissive factors multiply the texel. Left out under GIB_MATERIAL_PURE.
//   gib_material_emissive(m, uv), gib_material_emissive_filtered(m, uv, duv_dx, duv_dy)
//                                    m.emissive, times its emissive texture where it has one.
//   gib_alpha_accept_default(tri, u, v, seed)
//                                    interpolates the triangle's vertex uvs and decides a hit:
//                                    masks: alpha >= alpha_cutoff; opacity: a hash of (seed,
//                                    triangle) in [0,1) below the opacity (stochastic, the same
//                                    for a given seed and triangle). Needs the scene buffers:
//                                    include after GIB_SCENE_BUFFERS(...), or define
//                                    GIB_MATERIAL_PURE to leave it out.
#ifndef GIB_MATERIAL_GLSL
#define GIB_MATERIAL_GLSL

#include "scene.glsl"
#ifndef GIB_MATERIAL_PURE
#include "textures.glsl"
#endif

// Leaf ellipse: centred in uv, half-width 0.32, half-length 1/2.125 (0.47); reciprocals are
// exact floats.
#define GIB_LEAF_INV_HALF_WIDTH 3.125
#define GIB_LEAF_INV_HALF_LENGTH 2.125

// lowbias32 (Wellons): cheap, well-mixed 32-bit integer hash.
uint gib_material_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint gib_material_hash2(uint x, uint y) {
  return gib_material_hash(x ^ gib_material_hash(y + 0x9e3779b9u));
}

// Top 24 bits to [0, 1), exact in float.
float gib_material_hash01(uint h) {
  return float(h >> 8) * (1.0 / 16777216.0);
}

float gib_material_value_noise(vec2 p) {
  precise vec2 ip = floor(p);
  precise vec2 f = p - ip;
  int ix = int(ip.x);
  int iy = int(ip.y);
  float n00 = gib_material_hash01(gib_material_hash2(uint(ix), uint(iy)));
  float n10 = gib_material_hash01(gib_material_hash2(uint(ix + 1), uint(iy)));
  float n01 = gib_material_hash01(gib_material_hash2(uint(ix), uint(iy + 1)));
  float n11 = gib_material_hash01(gib_material_hash2(uint(ix + 1), uint(iy + 1)));
  precise vec2 s = f * f * (3.0 - 2.0 * f);
  precise float a = n00 + (n10 - n00) * s.x;
  precise float b = n01 + (n11 - n01) * s.x;
  precise float n = a + (b - a) * s.y;
  return n;
}

// 0 or 1: parity of the checker cell containing uv * scale.
float gib_material_checker(vec2 uv, float scale) {
  precise vec2 p = uv * scale;
  precise vec2 c = floor(p);
  precise float s = c.x + c.y;
  precise float parity = s - 2.0 * floor(s * 0.5);
  return parity;
}

vec3 gib_material_albedo(GpuMaterial m, vec2 uv) {
#ifndef GIB_MATERIAL_PURE
  if (m.texture == GIB_TEXTURE_IMAGE && m.base_color_texture != GIB_TEXTURE_NO_INDEX) {
    precise vec3 c = m.albedo * gib_texture_bilinear(m.base_color_texture, 0u, uv).rgb;
    return c;
  }
#endif
  if (m.texture == GIB_TEXTURE_CHECKER) {
    return gib_material_checker(uv, m.texture_scale) < 0.5 ? m.albedo : m.albedo2;
  }
  if (m.texture == GIB_TEXTURE_VALUE_NOISE) {
    precise vec2 p = uv * m.texture_scale;
    float n = gib_material_value_noise(p);
    precise vec3 c = m.albedo + (m.albedo2 - m.albedo) * n;
    return c;
  }
  return m.albedo;
}

float gib_material_alpha(GpuMaterial m, vec2 uv, uint hash_seed) {
  if (m.alpha == GIB_ALPHA_LEAF_MASK) {
    precise float x = (uv.x - 0.5) * GIB_LEAF_INV_HALF_WIDTH;
    precise float y = (uv.y - 0.5) * GIB_LEAF_INV_HALF_LENGTH;
    precise float r2 = x * x + y * y;
    return r2 <= 1.0 ? 1.0 : 0.0;
  }
  if (m.alpha == GIB_ALPHA_CHECKER_MASK) {
    return gib_material_checker(uv, m.texture_scale) < 0.5 ? 1.0 : 0.0;
  }
  if (m.alpha == GIB_ALPHA_OPACITY) return m.opacity;
#ifndef GIB_MATERIAL_PURE
  if (m.alpha == GIB_ALPHA_TEXTURE_MASK || m.alpha == GIB_ALPHA_TEXTURE_OPACITY) {
    if (m.base_color_texture == GIB_TEXTURE_NO_INDEX) return m.opacity;
    precise float a = m.opacity * gib_texture_bilinear(m.base_color_texture, 0u, uv).a;
    return a;
  }
#endif
  return 1.0;
}

vec3 gib_material_emissive(GpuMaterial m, vec2 uv) {
#ifndef GIB_MATERIAL_PURE
  if (m.emissive_texture != GIB_TEXTURE_NO_INDEX) {
    precise vec3 e = m.emissive * gib_texture_bilinear(m.emissive_texture, 0u, uv).rgb;
    return e;
  }
#endif
  return m.emissive;
}

vec3 gib_material_emissive_filtered(GpuMaterial m, vec2 uv, vec2 duv_dx, vec2 duv_dy) {
#ifndef GIB_MATERIAL_PURE
  if (m.emissive_texture != GIB_TEXTURE_NO_INDEX) {
    precise vec3 e = m.emissive * gib_texture_sample(m.emissive_texture, uv, duv_dx, duv_dy).rgb;
    return e;
  }
#endif
  return m.emissive;
}

// Procedural textures have no mips: average 4x4 samples over the pixel's UV footprint
// (the parallelogram spanned by the UV derivatives), which removes checker aliasing.
// Image textures have mips: one bilinear sample at the footprint's level instead.
vec3 gib_material_albedo_filtered(GpuMaterial m, vec2 uv, vec2 duv_dx, vec2 duv_dy) {
  if (m.texture == GIB_TEXTURE_NONE) return m.albedo;
#ifndef GIB_MATERIAL_PURE
  if (m.texture == GIB_TEXTURE_IMAGE) {
    if (m.base_color_texture == GIB_TEXTURE_NO_INDEX) return m.albedo;
    precise vec3 c = m.albedo * gib_texture_sample(m.base_color_texture, uv, duv_dx, duv_dy).rgb;
    return c;
  }
#endif
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      vec2 o = (vec2(i, j) + 0.5) / 4.0 - 0.5;
      sum += gib_material_albedo(m, uv + duv_dx * o.x + duv_dy * o.y);
    }
  return sum / 16.0;
}

#ifndef GIB_MATERIAL_PURE
vec2 gib_triangle_uv(uint triangle, float u, float v) {
  GpuTriangle tri = gib_triangles[triangle];
  GpuVertex a = gib_vertices[tri.i0];
  GpuVertex b = gib_vertices[tri.i1];
  GpuVertex c = gib_vertices[tri.i2];
  precise float w = 1.0 - u - v;
  precise vec2 uv = (vec2(a.u, a.v) * w + vec2(b.u, b.v) * u) + vec2(c.u, c.v) * v;
  return uv;
}

bool gib_alpha_accept_default(uint triangle, float u, float v, uint hash_seed) {
  GpuMaterial m = gib_materials[gib_instances[gib_triangles[triangle].instance].material];
  if (m.alpha == GIB_ALPHA_NONE) return true;
  float a = gib_material_alpha(m, gib_triangle_uv(triangle, u, v), hash_seed);
  if (m.alpha == GIB_ALPHA_OPACITY || m.alpha == GIB_ALPHA_TEXTURE_OPACITY) {
    return gib_material_hash01(gib_material_hash2(hash_seed, triangle)) < a;
  }
  return a >= m.alpha_cutoff;
}
#endif  // GIB_MATERIAL_PURE

#endif  // GIB_MATERIAL_GLSL
