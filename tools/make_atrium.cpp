// Writes cases/scenes/atrium.glb: a courtyard built from procedural geometry and
// procedural images, exported through gib::export_gltf. A 12 m x 12 m court open to the sky
// inside 7 m brick walls; along its north side a colonnade (six plaster columns, a roof slab,
// alpha-masked arch cards between the columns) that the roof keeps in shade; two clumps of
// alpha-masked foliage cards in the court. Textures (base colour, sRGB): brick 128x128, plaster
// 64x64, arch 64x64 and leaf 64x64 with alpha masks; the bricks' normal map (linear) 128x128. No lights, camera or sun: the scene file
// (cases/scenes/atrium.json) sets them.
//
//   cmake --build build --target gib_make_atrium && build/gib_make_atrium cases/scenes/atrium.glb
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "renderer/scene/gltf_export.h"
#include "renderer/scene/material_eval.h"
#include "renderer/scene/normal_map.h"
#include "renderer/scene/primitives.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/texture.h"

namespace {

using namespace gib;

uint8_t u8(float v) { return uint8_t(std::lround(std::fmin(std::fmax(v, 0.0f), 1.0f) * 255.0f)); }

// A deterministic value in [0, 1) per integer lattice point (the materials' hash).
float noise(uint32_t x, uint32_t y, uint32_t salt) { return material_hash01(material_hash2(x * 73856093u ^ salt, y)); }

// Running bond bricks, 4 courses by 2 bricks per tile, mortar lines 2 texels wide.
Texture brick_texture() {
  const uint32_t n = 128;
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t course = y / 32, shift = (course % 2) * 32, bx = (x + shift) % n / 64;
      const bool mortar = y % 32 < 2 || (x + shift) % 64 < 2;
      const float grain = 0.85f + 0.15f * noise(x, y, 1);
      const float tone = 0.8f + 0.35f * noise(bx + 2 * course, course, 2);
      const float r = mortar ? 0.72f * grain : 0.62f * tone * grain, g = mortar ? 0.68f * grain : 0.30f * tone * grain,
                  b = mortar ? 0.62f * grain : 0.22f * tone * grain;
      px.insert(px.end(), {u8(r), u8(g), u8(b), 255});
    }
  return make_texture("atrium/brick", n, n, px.data(), true);
}

// The bricks' tangent-space normal map (linear, glTF's convention: +x along u, +y up the image):
// brick faces flat, their edges bevelled 45 degrees over 2 texels down into the mortar joints of
// brick_texture, which are flat and recessed.
Texture brick_normal_texture() {
  const uint32_t n = 128;
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t shift = (y / 32 % 2) * 32, yy = y % 32, xx = (x + shift) % 64;
      Vec3 m{0, 0, 1};
      if (yy >= 2 && xx >= 2) {  // a brick texel: tilt towards the joints it is within 2 texels of
        if (yy - 2 < 2) m.y += 1;    // joint above (up the image): the face slopes up
        if (31 - yy < 2) m.y -= 1;   // joint below
        if (xx - 2 < 2) m.x -= 1;    // joint to the left (towards -u)
        if (63 - xx < 2) m.x += 1;   // joint to the right
      }
      const Vec3 t = encode_tangent_normal(normalize(m));
      px.insert(px.end(), {u8(t.x), u8(t.y), u8(t.z), 255});
    }
  return make_texture("atrium/brick_normal", n, n, px.data(), false);
}

// Warm plaster with a soft mottle (smoothed lattice noise).
Texture plaster_texture() {
  const uint32_t n = 64;
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const float m = 0.5f * material_value_noise({float(x) / 8, float(y) / 8}) + 0.5f * noise(x, y, 3);
      const float k = 0.82f + 0.12f * m;
      px.insert(px.end(), {u8(0.86f * k), u8(0.80f * k), u8(0.70f * k), 255});
    }
  return make_texture("atrium/plaster", n, n, px.data(), true);
}

// A 2 m x 1.75 m card: opaque plaster spandrels around a round arch springing 0.8 m above the
// card's bottom edge, radius 0.9 m; transparent inside the opening.
Texture arch_texture() {
  const uint32_t n = 64;
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / n, v = (float(y) + 0.5f) / n;  // v = 0: the top row
      const float mx = 2 * u - 1, my = (1 - v) * 1.75f;
      const bool open = my < 0.8f || mx * mx + (my - 0.8f) * (my - 0.8f) < 0.81f;
      const float k = 0.8f + 0.1f * noise(x, y, 4);
      px.insert(px.end(), {u8(0.88f * k), u8(0.82f * k), u8(0.72f * k), uint8_t(open ? 0 : 255)});
    }
  return make_texture("atrium/arch", n, n, px.data(), true);
}

// A leaf: a pointed ellipse along v with a darker midrib; transparent outside.
Texture leaf_texture() {
  const uint32_t n = 64;
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / n - 0.5f, v = (float(y) + 0.5f) / n - 0.5f;
      const float half_width = 0.34f * std::sqrt(std::fmax(0.0f, 1.0f - 4.0f * v * v)) * (1.0f - 0.6f * std::fabs(v));
      const bool inside = std::fabs(u) < half_width;
      const float k = (std::fabs(u) < 0.02f ? 0.6f : 1.0f) * (0.85f + 0.15f * noise(x, y, 5));
      px.insert(px.end(), {u8(0.16f * k), u8(0.42f * k), u8(0.10f * k), uint8_t(inside ? 255 : 0)});
    }
  return make_texture("atrium/leaf", n, n, px.data(), true);
}

// A rectangle from `corner` along a (u) and b (v), uvs repeating every `tile` metres; glTF's v
// runs down the image, so v = 0 is at corner + b.
Mesh panel(Vec3 corner, Vec3 a, Vec3 b, float tile) {
  Mesh m;
  const Vec3 n = normalize(cross(a, b));
  const float ru = length(a) / tile, rv = length(b) / tile;
  m.positions = {corner, corner + a, corner + a + b, corner + b};
  m.normals = {n, n, n, n};
  m.uvs = {{0, rv}, {ru, rv}, {ru, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// A box with its faces' uvs scaled to `tile` metres.
Mesh tiled_box(Vec3 size, float tile) {
  Mesh m = make_box(size);
  for (size_t i = 0; i < m.uvs.size(); ++i) {
    const Vec3 n = m.normals[i];
    const float su = std::fabs(n.x) > 0.5f ? size.z : size.x;
    const float sv = std::fabs(n.y) > 0.5f ? size.z : size.y;
    m.uvs[i] = {m.uvs[i].x * su / tile, m.uvs[i].y * sv / tile};
  }
  return m;
}

struct Builder {
  Scene s;
  uint32_t material(const std::string& name, Vec3 albedo, int32_t texture, AlphaKind alpha = AlphaKind::none) {
    Material m;
    m.name = name;
    m.albedo = albedo;
    m.roughness = 0.9f;
    m.base_color_texture = texture;
    m.texture = texture >= 0 ? TextureKind::image : TextureKind::none;
    m.alpha = alpha;
    m.alpha_cutoff = 0.5f;
    m.opacity = 1.0f;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
  }
  uint32_t mesh(Mesh m, const std::string& name) {
    m.name = name;
    s.meshes.push_back(std::move(m));
    return uint32_t(s.meshes.size() - 1);
  }
  void place(const std::string& name, uint32_t mesh, uint32_t material, Vec3 at) {
    Instance i;
    i.name = name;
    i.mesh = mesh;
    i.material = material;
    i.transform = Mat4::translation(at);
    s.instances.push_back(std::move(i));
  }
};

Scene build() {
  Builder b;
  b.s.textures = {brick_texture(), plaster_texture(), arch_texture(), leaf_texture(), brick_normal_texture()};
  const uint32_t brick = b.material("brick", {1, 1, 1}, 0), plaster = b.material("plaster", {1, 1, 1}, 1);
  b.s.materials[brick].normal_texture = 4;
  const uint32_t stone = b.material("paving", {0.9f, 0.9f, 0.85f}, 1);
  const uint32_t arch = b.material("arch", {1, 1, 1}, 2, AlphaKind::texture_mask);
  const uint32_t leaf = b.material("leaves", {1, 1, 1}, 3, AlphaKind::texture_mask);
  const uint32_t soil = b.material("planter", {0.35f, 0.3f, 0.27f}, -1);

  const float h = 7.0f;  // wall height
  b.place("floor", b.mesh(panel({-6, 0, 6}, {12, 0, 0}, {0, 0, -12}, 2.0f), "floor"), stone, {0, 0, 0});
  b.place("wall_north", b.mesh(panel({-6, 0, -6}, {12, 0, 0}, {0, h, 0}, 2.0f), "wall_n"), brick, {0, 0, 0});
  b.place("wall_south", b.mesh(panel({6, 0, 6}, {-12, 0, 0}, {0, h, 0}, 2.0f), "wall_s"), brick, {0, 0, 0});
  b.place("wall_west", b.mesh(panel({-6, 0, 6}, {0, 0, -12}, {0, h, 0}, 2.0f), "wall_w"), brick, {0, 0, 0});
  b.place("wall_east", b.mesh(panel({6, 0, -6}, {0, 0, 12}, {0, h, 0}, 2.0f), "wall_e"), brick, {0, 0, 0});
  // The colonnade: roof over z in [-6, -3.5], columns on its open edge, arches between them.
  b.place("roof", b.mesh(tiled_box({12, 0.3f, 2.5f}, 2.0f), "roof"), plaster, {0, 3.5f, -4.75f});
  const uint32_t column = b.mesh(tiled_box({0.4f, 3.35f, 0.4f}, 1.0f), "column");
  for (int i = 0; i < 6; ++i)
    b.place("column" + std::to_string(i), column, plaster, {-5.0f + 2.0f * float(i), 1.675f, -3.7f});
  const uint32_t card = b.mesh(panel({-1, 0, 0}, {2, 0, 0}, {0, 1.75f, 0}, 1.0f), "arch_card");
  // The panel's uv repeats once per metre: a 2 x 1.75 card spans u in [0, 2]; scale it to one arch.
  for (Vec2& uv : b.s.meshes[card].uvs) uv = {uv.x / 2.0f, uv.y / 1.75f};
  for (int i = 0; i < 5; ++i) b.place("arch" + std::to_string(i), card, arch, {-4.0f + 2.0f * float(i), 1.6f, -3.5f});
  // Foliage: two planters with leaf clumps.
  const uint32_t planter = b.mesh(tiled_box({1.2f, 0.5f, 1.2f}, 1.0f), "planter");
  const uint32_t clump = b.mesh(make_leaf_cards(90, {1.6f, 1.4f, 1.6f}, {0.4f, 0.4f}, 18), "leaf_cards");
  for (int side = 0; side < 2; ++side) {
    const float x = side ? 3.0f : -3.0f;
    b.place(std::string("planter") + (side ? "_e" : "_w"), planter, soil, {x, 0.25f, 1.5f});
    b.place(std::string("foliage") + (side ? "_e" : "_w"), clump, leaf, {x, 1.3f, 1.5f});
  }
  b.s.camera.position = {0, 1.7f, 5.5f};
  b.s.camera.target = {0, 1.8f, -4};
  b.s.camera.fov_y_deg = 70;
  return b.s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.glb\n", argv[0]);
    return 2;
  }
  try {
    const Scene s = build();
    const GltfExportReport r = export_gltf(s, argv[1]);
    const uint64_t bytes = textures_bytes(s.textures);
    std::printf("%s: %u meshes, %u nodes, %u materials, %zu textures (%llu bytes with mips)\n", argv[1], r.meshes,
                r.nodes, r.materials, s.textures.size(), static_cast<unsigned long long>(bytes));
    for (const std::string& l : r.lossy) std::printf("  not exported: %s\n", l.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
