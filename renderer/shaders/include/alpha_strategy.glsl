// Alpha strategies for ray traversals (AC Shadows, "Alpha sampling": the reference alpha test,
// an any-hit limit, dithering the average opacity, the opaque approximation), chosen per run
// (Settings::alpha, common options alpha_strategy and alpha_any_hit_limit; the frame constants'
// alpha_info). CPU mirror: renderer/scene/material_eval.h (alpha_strategy_accept,
// alpha_ray_key), same formulas and the same traversal order, so the CPU BVH reproduces the GPU's
// hits ray for ray (tests/test_bvh.cpp).
//
//   gib_alpha_ray_key(o, d)       a per-ray hash of the ray's bits (the dither's noise; the seed
//                                 uses blue noise per ray, we have none: white noise)
//   gib_alpha_strategy_accept(triangle, u, v, calls, ray_key, hash_seed, strategy, limit)
//     for a candidate hit of an alpha-tested triangle (others always accept):
//     opaque (3): accept (alpha ignored);
//     opaque approximation (2): accept where the hit lies inside the triangle scaled about its
//       centroid by s = sqrt(average opacity), i.e. every barycentric >= (1 - s) / 3: the shrunk
//       triangle traced as opaque, without a second vertex buffer (the BVH keeps the full-size
//       boxes, so traversal visits what a rebuilt BVH would cull);
//     otherwise the candidate is one any-hit call: calls += 1; past `limit` (> 0) accept (forced
//       opaque); dither (1): accept when hash(ray_key, calls) < average opacity (no mask fetch,
//       a new value per call); test (0): the mask (gib_alpha_accept_default).
// Needs material.glsl (and the scene buffers).
#ifndef GIB_ALPHA_STRATEGY_GLSL
#define GIB_ALPHA_STRATEGY_GLSL

#define GIB_ALPHA_STRATEGY_TEST 0u
#define GIB_ALPHA_STRATEGY_DITHER 1u
#define GIB_ALPHA_STRATEGY_OPAQUE_APPROX 2u
#define GIB_ALPHA_STRATEGY_OPAQUE 3u

uint gib_alpha_ray_key(vec3 o, vec3 d) {
  uvec3 a = floatBitsToUint(o), b = floatBitsToUint(d);
  uint h = gib_material_hash2(a.x, a.y);
  h = gib_material_hash2(h, a.z);
  h = gib_material_hash2(h, b.x);
  h = gib_material_hash2(h, b.y);
  return gib_material_hash2(h, b.z);
}

bool gib_alpha_strategy_accept(uint triangle, float u, float v, inout uint calls, uint ray_key, uint hash_seed,
                               uint strategy, uint limit) {
  GpuMaterial m = gib_materials[gib_instances[gib_triangles[triangle].instance].material];
  if (m.alpha == GIB_ALPHA_NONE) return true;
  if (strategy == GIB_ALPHA_STRATEGY_OPAQUE) return true;
  if (strategy == GIB_ALPHA_STRATEGY_OPAQUE_APPROX) {
    precise float s = sqrt(m.avg_opacity);
    precise float edge = (1.0 - s) / 3.0;
    precise float w = 1.0 - u - v;
    return w >= edge && u >= edge && v >= edge;
  }
  calls += 1u;
  if (limit != 0u && calls > limit) return true;
  if (strategy == GIB_ALPHA_STRATEGY_DITHER)
    return gib_material_hash01(gib_material_hash2(ray_key, calls)) < m.avg_opacity;
  return gib_alpha_accept_default(triangle, u, v, hash_seed);
}

#endif
