// CPU mirror of renderer/shaders/include/material.glsl: procedural albedo textures and alpha
// masks, with the same hash, formulas and operation order, so tests can compare the two and
// CPU references (BVH alpha testing, path tracer checks) see the same materials as the GPU.
#pragma once
#include <cstdint>
#include <vector>

#include "renderer/scene/math.h"
#include "renderer/scene/scene.h"

namespace gib {

// lowbias32 and helpers (gib_material_hash, gib_material_hash2, gib_material_hash01).
uint32_t material_hash(uint32_t x);
uint32_t material_hash2(uint32_t x, uint32_t y);
float material_hash01(uint32_t h);  // top 24 bits to [0, 1)
float material_value_noise(Vec2 p);
float material_checker(Vec2 uv, float scale);  // 0 or 1

// Image textures read `textures` (pack_textures' words, FlatScene::textures) at mip level 0, as
// the shaders' unfiltered functions do; without it (null) an image texture reads as white.
Vec3 material_albedo(const GpuMaterial& m, Vec2 uv, const std::vector<uint32_t>* textures = nullptr);
float material_alpha(const GpuMaterial& m, Vec2 uv, uint32_t hash_seed, const std::vector<uint32_t>* textures = nullptr);
Vec3 material_emissive(const GpuMaterial& m, Vec2 uv, const std::vector<uint32_t>* textures = nullptr);

// Vertex uvs interpolated at barycentrics (u, v) of vertices 1 and 2 (gib_triangle_uv).
Vec2 triangle_uv(const FlatScene& scene, uint32_t triangle, float u, float v);
// gib_alpha_accept_default: masks pass at alpha >= alpha_cutoff; opacity (and texture opacity)
// passes when the hash of (seed, triangle) is below it. Image textures: scene.textures.
bool alpha_accept_default(const FlatScene& scene, uint32_t triangle, float u, float v,
                          uint32_t hash_seed);

// alpha_strategy.glsl: the alpha strategies of ray traversals (AlphaStrategy in settings.h, as
// numbers: 0 test, 1 dither, 2 opaque approximation, 3 opaque). One AlphaRay per traversal: calls
// counts the any-hit calls it made, key is alpha_ray_key(o, d).
uint32_t alpha_ray_key(Vec3 o, Vec3 d);
struct AlphaRay {
  uint32_t strategy = 0, limit = 0;
  uint32_t calls = 0, key = 0;
};
bool alpha_strategy_accept(const FlatScene& scene, AlphaRay& ray, uint32_t triangle, float u, float v,
                           uint32_t hash_seed);
// The mean of a material's alpha over the texel centres (a raster of 1/grid UV texels) inside
// the UV triangles of the meshes that use it: the seed bakes its average opacity "by rasterising
// each mesh onto its alpha texture", our masks are procedural in UV, so the raster is of UV
// space. A triangle covering no texel centre counts its UV centroid. 1 for a material without
// alpha or one no instance uses; its opacity for AlphaKind::opacity. Texture masks and texture
// opacities average their texture's alpha (level 0, bilinear) at the same centres. Per material (the seed's is
// per mesh; here every mesh of a material shares its value).
std::vector<float> bake_average_opacity(const Scene& scene, uint32_t grid = 64);

// brdf.glsl gib_sheen_lobe: the cloth class's sheen x D_charlie x V_neubelt (1/sr).
float sheen_lobe(float sheen, float roughness, Vec3 n, Vec3 wi, Vec3 wo);
// The Charlie distribution alone (a = max(roughness^2, 0.01)), for its normalisation test.
float sheen_distribution(float roughness, float cos_h);

// brdf.glsl's glossy class (GGX specular layer over a Lambertian base), same formulas and
// operation order as gib_ggx_* / gib_glossy_*; GlossyLobes.spec and .diffuse are f (1/sr).
inline constexpr float kGgxMinAlpha = 0.002f;
float ggx_alpha(float roughness);
float ggx_d(float a, float nh);
float ggx_v(float a, float nl, float nv);  // G2 / (4 nl nv), height-correlated Smith
float ggx_g1(float a, float nv);
Vec3 schlick(Vec3 f0, float c);
struct GlossyLobes {
  Vec3 spec{0, 0, 0}, diffuse{0, 0, 0};
};
GlossyLobes glossy_eval(Vec3 n, Vec3 wo, Vec3 wi, Vec3 albedo, float roughness, float metalness);
float glossy_spec_probability(Vec3 n, Vec3 wo, Vec3 albedo, float metalness);
Vec3 ggx_sample_vndf(Vec3 n, Vec3 wo, float a, float u0, float u1);  // a microfacet normal
float glossy_pdf(Vec3 n, Vec3 wo, Vec3 wi, float roughness, float p_spec);
Vec3 glossy_sample(Vec3 n, Vec3 wo, float roughness, float p_spec, float u0, float u1, float pick);
// The specular lobe's directional albedo E(n.wo) = integral of D V cos over wi (Fresnel 1, a
// white metal), by midpoint quadrature over (theta, phi) of wi: `steps` x 2 `steps` cells.
double ggx_directional_albedo(float roughness, float cos_view, int steps = 512);

// decals.glsl: gib_decal_weight and gib_decals_at (albedo' = albedo * k + c; returns c, k in w).
float decal_weight(const GpuDecal& d, Vec3 x, Vec3 n);
Vec4 decals_at(const std::vector<GpuDecal>& decals, Vec3 x, Vec3 n);
Vec3 decal_blend(Vec3 albedo, Vec4 kc);

}  // namespace gib
