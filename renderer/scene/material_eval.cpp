// Must round like material.glsl (precise).
#include "renderer/scene/fp_contract_off.h"

#include "renderer/scene/material_eval.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gib {
namespace {
constexpr float kLeafInvHalfWidth = 3.125f;   // GIB_LEAF_INV_HALF_WIDTH
constexpr float kLeafInvHalfLength = 2.125f;  // GIB_LEAF_INV_HALF_LENGTH
}  // namespace

uint32_t material_hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint32_t material_hash2(uint32_t x, uint32_t y) { return material_hash(x ^ material_hash(y + 0x9e3779b9u)); }

float material_hash01(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

float material_value_noise(Vec2 p) {
  const float ipx = std::floor(p.x), ipy = std::floor(p.y);
  const float fx = p.x - ipx, fy = p.y - ipy;
  const int ix = int(ipx), iy = int(ipy);
  const float n00 = material_hash01(material_hash2(uint32_t(ix), uint32_t(iy)));
  const float n10 = material_hash01(material_hash2(uint32_t(ix + 1), uint32_t(iy)));
  const float n01 = material_hash01(material_hash2(uint32_t(ix), uint32_t(iy + 1)));
  const float n11 = material_hash01(material_hash2(uint32_t(ix + 1), uint32_t(iy + 1)));
  const float sx = fx * fx * (3.0f - 2.0f * fx);
  const float sy = fy * fy * (3.0f - 2.0f * fy);
  const float a = n00 + (n10 - n00) * sx;
  const float b = n01 + (n11 - n01) * sx;
  return a + (b - a) * sy;
}

float material_checker(Vec2 uv, float scale) {
  const float cx = std::floor(uv.x * scale), cy = std::floor(uv.y * scale);
  const float s = cx + cy;
  return s - 2.0f * std::floor(s * 0.5f);
}

Vec3 material_albedo(const GpuMaterial& m, Vec2 uv, const std::vector<uint32_t>* textures) {
  const Vec3 a{m.albedo[0], m.albedo[1], m.albedo[2]};
  const Vec3 b{m.albedo2[0], m.albedo2[1], m.albedo2[2]};
  switch (static_cast<TextureKind>(m.texture)) {
    case TextureKind::image: {
      if (!textures || m.base_color_texture == kTextureNone) return a;
      const Vec4 t = texture_bilinear(*textures, m.base_color_texture, 0, uv);
      return {a.x * t.x, a.y * t.y, a.z * t.z};
    }
    case TextureKind::checker:
      return material_checker(uv, m.texture_scale) < 0.5f ? a : b;
    case TextureKind::value_noise: {
      const float n = material_value_noise({uv.x * m.texture_scale, uv.y * m.texture_scale});
      return {a.x + (b.x - a.x) * n, a.y + (b.y - a.y) * n, a.z + (b.z - a.z) * n};
    }
    default:
      return a;
  }
}

float material_alpha(const GpuMaterial& m, Vec2 uv, uint32_t /*hash_seed*/, const std::vector<uint32_t>* textures) {
  switch (static_cast<AlphaKind>(m.alpha)) {
    case AlphaKind::leaf_mask: {
      const float x = (uv.x - 0.5f) * kLeafInvHalfWidth;
      const float y = (uv.y - 0.5f) * kLeafInvHalfLength;
      return x * x + y * y <= 1.0f ? 1.0f : 0.0f;
    }
    case AlphaKind::checker_mask:
      return material_checker(uv, m.texture_scale) < 0.5f ? 1.0f : 0.0f;
    case AlphaKind::opacity:
      return m.opacity;
    case AlphaKind::texture_mask:
    case AlphaKind::texture_opacity:
      if (!textures || m.base_color_texture == kTextureNone) return m.opacity;
      return m.opacity * texture_bilinear(*textures, m.base_color_texture, 0, uv).w;
    default:
      return 1.0f;
  }
}

Vec3 material_emissive(const GpuMaterial& m, Vec2 uv, const std::vector<uint32_t>* textures) {
  const Vec3 e{m.emissive[0], m.emissive[1], m.emissive[2]};
  if (!textures || m.emissive_texture == kTextureNone) return e;
  const Vec4 t = texture_bilinear(*textures, m.emissive_texture, 0, uv);
  return {e.x * t.x, e.y * t.y, e.z * t.z};
}

Vec2 triangle_uv(const FlatScene& scene, uint32_t triangle, float u, float v) {
  const GpuTriangle& t = scene.triangles[triangle];
  const GpuVertex& a = scene.vertices[t.i0];
  const GpuVertex& b = scene.vertices[t.i1];
  const GpuVertex& c = scene.vertices[t.i2];
  const float w = 1.0f - u - v;
  return {(a.u * w + b.u * u) + c.u * v, (a.v * w + b.v * u) + c.v * v};
}

bool alpha_accept_default(const FlatScene& scene, uint32_t triangle, float u, float v,
                          uint32_t hash_seed) {
  const GpuMaterial& m =
      scene.materials[scene.instances[scene.triangles[triangle].instance].material];
  if (static_cast<AlphaKind>(m.alpha) == AlphaKind::none) return true;
  const float a = material_alpha(m, triangle_uv(scene, triangle, u, v), hash_seed, &scene.textures);
  if (static_cast<AlphaKind>(m.alpha) == AlphaKind::opacity ||
      static_cast<AlphaKind>(m.alpha) == AlphaKind::texture_opacity) {
    return material_hash01(material_hash2(hash_seed, triangle)) < a;
  }
  return a >= m.alpha_cutoff;
}

uint32_t alpha_ray_key(Vec3 o, Vec3 d) {
  auto bits = [](float f) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
  };
  uint32_t h = material_hash2(bits(o.x), bits(o.y));
  h = material_hash2(h, bits(o.z));
  h = material_hash2(h, bits(d.x));
  h = material_hash2(h, bits(d.y));
  return material_hash2(h, bits(d.z));
}

bool alpha_strategy_accept(const FlatScene& scene, AlphaRay& ray, uint32_t triangle, float u, float v,
                           uint32_t hash_seed) {
  const GpuMaterial& m = scene.materials[scene.instances[scene.triangles[triangle].instance].material];
  if (m.alpha == uint32_t(AlphaKind::none)) return true;
  if (ray.strategy == 3) return true;  // opaque
  if (ray.strategy == 2) {             // opaque approximation
    const float s = std::sqrt(m.avg_opacity);
    const float edge = (1.0f - s) / 3.0f;
    const float w = 1.0f - u - v;
    return w >= edge && u >= edge && v >= edge;
  }
  ray.calls += 1;
  if (ray.limit != 0 && ray.calls > ray.limit) return true;
  if (ray.strategy == 1) return material_hash01(material_hash2(ray.key, ray.calls)) < m.avg_opacity;
  return alpha_accept_default(scene, triangle, u, v, hash_seed);
}

std::vector<float> bake_average_opacity(const Scene& scene, uint32_t grid) {
  std::vector<double> sum(scene.materials.size(), 0.0), count(scene.materials.size(), 0.0);
  std::vector<GpuMaterial> gpu(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) gpu[i] = material_to_gpu(scene.materials[i]);
  const std::vector<uint32_t> textures = scene.textures.empty() ? std::vector<uint32_t>{} : pack_textures(scene.textures);
  auto masked = [](AlphaKind k) {
    return k == AlphaKind::leaf_mask || k == AlphaKind::checker_mask || k == AlphaKind::texture_mask ||
           k == AlphaKind::texture_opacity;
  };
  // Each (mesh, material) pair once: instances of one mesh share its UVs.
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const Instance& inst : scene.instances)
    if (inst.mesh < scene.meshes.size() && inst.material < scene.materials.size() &&
        masked(scene.materials[inst.material].alpha))
      pairs.emplace_back(inst.mesh, inst.material);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const double g = grid;
  for (auto [mesh_index, material] : pairs) {
    const Mesh& mesh = scene.meshes[mesh_index];
    if (mesh.uvs.size() < mesh.positions.size()) continue;  // no UVs: nothing to rasterise
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1], ic = mesh.indices[t + 2];
      if (ia >= mesh.uvs.size() || ib >= mesh.uvs.size() || ic >= mesh.uvs.size()) continue;
      const Vec2 a = mesh.uvs[ia], b = mesh.uvs[ib], c = mesh.uvs[ic];
      auto edge = [](Vec2 p, Vec2 q, double x, double y) { return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x); };
      const double area = edge(a, b, c.x, c.y);
      const double x0 = std::floor(std::min({a.x, b.x, c.x}) * g), x1 = std::ceil(std::max({a.x, b.x, c.x}) * g);
      const double y0 = std::floor(std::min({a.y, b.y, c.y}) * g), y1 = std::ceil(std::max({a.y, b.y, c.y}) * g);
      double tri_sum = 0, tri_count = 0;
      if (area != 0 && std::isfinite(area) && (x1 - x0) * (y1 - y0) <= 4.0 * g * g)
        for (double j = y0; j < y1; ++j)
          for (double i = x0; i < x1; ++i) {
            const double x = (i + 0.5) / g, y = (j + 0.5) / g;
            const double e0 = edge(b, c, x, y) * area, e1 = edge(c, a, x, y) * area, e2 = edge(a, b, x, y) * area;
            if (e0 < 0 || e1 < 0 || e2 < 0) continue;
            // A centre on an edge is shared with the neighbour across it: half a texel each.
            const double w = (e0 > 0 && e1 > 0 && e2 > 0) ? 1.0 : 0.5;
            tri_sum += w * material_alpha(gpu[material], {float(x), float(y)}, 0, &textures);
            tri_count += w;
          }
      if (tri_count == 0) {  // smaller than a texel (or degenerate / huge): its centroid
        tri_sum = material_alpha(gpu[material], {(a.x + b.x + c.x) / 3.0f, (a.y + b.y + c.y) / 3.0f}, 0, &textures);
        tri_count = 1;
      }
      sum[material] += tri_sum;
      count[material] += tri_count;
    }
  }
  std::vector<float> out(scene.materials.size(), 1.0f);
  for (size_t i = 0; i < out.size(); ++i) {
    if (scene.materials[i].alpha == AlphaKind::opacity) out[i] = scene.materials[i].opacity;
    else if (count[i] > 0) out[i] = float(sum[i] / count[i]);
  }
  return out;
}

float sheen_distribution(float roughness, float cos_h) {
  const float a = std::fmax(roughness * roughness, 0.01f);
  const float inv_a = 1.0f / a;
  const float sin2 = std::fmax(1.0f - cos_h * cos_h, 0.0f);
  return (2.0f + inv_a) * std::pow(sin2, 0.5f * inv_a) / (2.0f * 3.14159265358979f);
}

float sheen_lobe(float sheen, float roughness, Vec3 n, Vec3 wi, Vec3 wo) {
  const float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0f && nv > 0.0f)) return 0.0f;
  const Vec3 h = normalize(wi + wo);
  const float nh = std::clamp(dot(n, h), 0.0f, 1.0f);
  const float v = 1.0f / (4.0f * (nl + nv - nl * nv));
  return sheen * sheen_distribution(roughness, nh) * v;
}

float decal_weight(const GpuDecal& d, Vec3 x, Vec3 n) {
  const Vec3 r{x.x - d.centre[0], x.y - d.centre[1], x.z - d.centre[2]};
  auto local = [&](const float* a) { return (a[0] * r.x + a[1] * r.y + a[2] * r.z) * a[3]; };
  const float lx = local(d.axis_x), ly = local(d.axis_y), lz = local(d.axis_z);
  if (!(std::fabs(lx) <= 0.5f && std::fabs(ly) <= 0.5f && std::fabs(lz) <= 0.5f)) return 0.0f;
  const float r2 = lx * lx + ly * ly;
  if (d.centre[3] != 0.0f && r2 > 0.25f) return 0.0f;  // disc
  const float c = d.axis_z[0] * n.x + d.axis_z[1] * n.y + d.axis_z[2] * n.z;
  const float fade = std::clamp((c - 0.25f) * 4.0f, 0.0f, 1.0f);
  return d.albedo[3] * fade;
}

Vec4 decals_at(const std::vector<GpuDecal>& decals, Vec3 x, Vec3 n) {
  Vec3 c{0, 0, 0};
  float k = 1.0f;
  for (const GpuDecal& d : decals) {
    const float w = decal_weight(d, x, n);
    if (w <= 0.0f) continue;
    c = c * (1.0f - w) + Vec3{d.albedo[0], d.albedo[1], d.albedo[2]} * w;
    k = k * (1.0f - w);
  }
  return {c.x, c.y, c.z, k};
}

Vec3 decal_blend(Vec3 albedo, Vec4 kc) { return albedo * kc.w + Vec3{kc.x, kc.y, kc.z}; }

}  // namespace gib
