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

Vec3 material_albedo(const GpuMaterial& m, Vec2 uv);
float material_alpha(const GpuMaterial& m, Vec2 uv, uint32_t hash_seed);

// Vertex uvs interpolated at barycentrics (u, v) of vertices 1 and 2 (gib_triangle_uv).
Vec2 triangle_uv(const FlatScene& scene, uint32_t triangle, float u, float v);
// gib_alpha_accept_default: masks pass at alpha >= alpha_cutoff; opacity passes when the
// hash of (seed, triangle) is below it.
bool alpha_accept_default(const FlatScene& scene, uint32_t triangle, float u, float v,
                          uint32_t hash_seed);

// brdf.glsl gib_sheen_lobe: the cloth class's sheen x D_charlie x V_neubelt (1/sr).
float sheen_lobe(float sheen, float roughness, Vec3 n, Vec3 wi, Vec3 wo);
// The Charlie distribution alone (a = max(roughness^2, 0.01)), for its normalisation test.
float sheen_distribution(float roughness, float cos_h);

// decals.glsl: gib_decal_weight and gib_decals_at (albedo' = albedo * k + c; returns c, k in w).
float decal_weight(const GpuDecal& d, Vec3 x, Vec3 n);
Vec4 decals_at(const std::vector<GpuDecal>& decals, Vec3 x, Vec3 n);
Vec3 decal_blend(Vec3 albedo, Vec4 kc);

}  // namespace gib
