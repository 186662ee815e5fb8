#include "renderer/scene/primitives.h"

#include <algorithm>
#include <numbers>

namespace gib {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

struct Frame {
  Vec3 u, v, n;
};

Frame facing_frame(Facing f) {
  switch (f) {
    case Facing::pos_x: return {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}};
    case Facing::neg_x: return {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}};
    case Facing::pos_y: return {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    case Facing::neg_y: return {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    case Facing::pos_z: return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case Facing::neg_z: return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  }
  return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
}

uint32_t vertex_count(const Mesh& m) { return static_cast<uint32_t>(m.positions.size()); }

void add_vertex(Mesh& m, Vec3 p, Vec3 n, Vec2 uv) {
  m.positions.push_back(p);
  m.normals.push_back(n);
  m.uvs.push_back(uv);
}

void add_triangle(Mesh& m, uint32_t a, uint32_t b, uint32_t c) {
  m.indices.insert(m.indices.end(), {a, b, c});
}

// A rectangle centred at `center` spanning `w` along `u` and `h` along `v`, facing u x v.
void add_rect(Mesh& m, Vec3 center, Vec3 u, Vec3 v, float w, float h) {
  Vec3 n = normalize(cross(u, v));
  uint32_t base = vertex_count(m);
  Vec3 du = u * (0.5f * w), dv = v * (0.5f * h);
  add_vertex(m, center - du - dv, n, {0, 0});
  add_vertex(m, center + du - dv, n, {1, 0});
  add_vertex(m, center + du + dv, n, {1, 1});
  add_vertex(m, center - du + dv, n, {0, 1});
  add_triangle(m, base, base + 1, base + 2);
  add_triangle(m, base, base + 2, base + 3);
}

Vec3 abs3(Vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }

// PCG32 (O'Neill): tiny, fast and, unlike std:: distributions, specified to the bit, so
// leaf cards are identical across standard libraries.
class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed) {
    state_ = 0;
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + 1442695040888963407ull;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }  // [0,1)

 private:
  uint64_t state_;
};

}  // namespace

std::optional<Facing> parse_facing(std::string_view s) {
  for (Facing f : {Facing::pos_x, Facing::neg_x, Facing::pos_y, Facing::neg_y, Facing::pos_z, Facing::neg_z})
    if (facing_name(f) == s) return f;
  return std::nullopt;
}

std::string_view facing_name(Facing f) {
  switch (f) {
    case Facing::pos_x: return "+x";
    case Facing::neg_x: return "-x";
    case Facing::pos_y: return "+y";
    case Facing::neg_y: return "-y";
    case Facing::pos_z: return "+z";
    case Facing::neg_z: return "-z";
  }
  return "?";
}

Vec3 facing_normal(Facing f) { return facing_frame(f).n; }

Mesh make_box(Vec3 size) {
  Mesh m;
  m.name = "box";
  m.closed = true;
  for (Facing f : {Facing::pos_x, Facing::neg_x, Facing::pos_y, Facing::neg_y, Facing::pos_z, Facing::neg_z}) {
    Frame fr = facing_frame(f);
    float w = dot(abs3(fr.u), size), h = dot(abs3(fr.v), size), d = dot(abs3(fr.n), size);
    add_rect(m, fr.n * (0.5f * d), fr.u, fr.v, w, h);
  }
  return m;
}

Mesh make_quad(Vec2 size, Facing facing) {
  Mesh m;
  m.name = "quad";
  Frame fr = facing_frame(facing);
  add_rect(m, {0, 0, 0}, fr.u, fr.v, size.x, size.y);
  return m;
}

Mesh make_sphere(float radius, uint32_t segments) {
  Mesh m;
  m.name = "sphere";
  m.closed = true;
  segments = std::max(segments, 3u);
  uint32_t rings = std::max(segments / 2, 2u);
  // Vertex grid with a duplicated seam column so UVs do not wrap backwards.
  for (uint32_t i = 0; i <= rings; ++i) {
    float theta = kPi * static_cast<float>(i) / static_cast<float>(rings);
    for (uint32_t j = 0; j <= segments; ++j) {
      float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
      if (i == 0) n = {0, 1, 0};
      if (i == rings) n = {0, -1, 0};
      add_vertex(m, n * radius, n,
                 {static_cast<float>(j) / static_cast<float>(segments), static_cast<float>(i) / static_cast<float>(rings)});
    }
  }
  uint32_t stride = segments + 1;
  for (uint32_t i = 0; i < rings; ++i)
    for (uint32_t j = 0; j < segments; ++j) {
      uint32_t v00 = i * stride + j, v01 = v00 + 1, v10 = v00 + stride, v11 = v10 + 1;
      if (i != 0) add_triangle(m, v00, v01, v10);          // collapses at the north pole
      if (i != rings - 1) add_triangle(m, v01, v11, v10);  // collapses at the south pole
    }
  return m;
}

Mesh make_cylinder(float radius, float height, uint32_t segments, bool capped) {
  Mesh m;
  m.name = "cylinder";
  segments = std::max(segments, 3u);
  float y0 = -0.5f * height, y1 = 0.5f * height;
  for (uint32_t j = 0; j <= segments; ++j) {
    float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
    Vec3 n{std::cos(phi), 0, std::sin(phi)};
    float u = static_cast<float>(j) / static_cast<float>(segments);
    add_vertex(m, {n.x * radius, y0, n.z * radius}, n, {u, 0});
    add_vertex(m, {n.x * radius, y1, n.z * radius}, n, {u, 1});
  }
  for (uint32_t j = 0; j < segments; ++j) {
    uint32_t b0 = 2 * j, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    add_triangle(m, b0, t0, b1);
    add_triangle(m, t0, t1, b1);
  }
  if (!capped) return m;
  m.closed = true;
  for (int side = 0; side < 2; ++side) {
    float y = side == 0 ? y1 : y0;
    Vec3 n{0, side == 0 ? 1.0f : -1.0f, 0};
    uint32_t center = vertex_count(m);
    add_vertex(m, {0, y, 0}, n, {0.5f, 0.5f});
    for (uint32_t j = 0; j < segments; ++j) {
      float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      float c = std::cos(phi), s = std::sin(phi);
      add_vertex(m, {c * radius, y, s * radius}, n, {0.5f + 0.5f * c, 0.5f + 0.5f * s});
    }
    for (uint32_t j = 0; j < segments; ++j) {
      uint32_t a = center + 1 + j, b = center + 1 + (j + 1) % segments;
      if (side == 0)
        add_triangle(m, center, b, a);
      else
        add_triangle(m, center, a, b);
    }
  }
  return m;
}

Mesh make_thin_slab(Vec2 size, float thickness, Facing facing) {
  Frame fr = facing_frame(facing);
  Mesh m = make_box(abs3(fr.u) * size.x + abs3(fr.v) * size.y + abs3(fr.n) * thickness);
  m.name = "thin_slab";
  return m;
}

Mesh make_leaf_cards(uint32_t count, Vec3 region, Vec2 card_size, uint32_t seed) {
  Mesh m;
  m.name = "leaf_cards";
  Pcg32 rng(seed);
  for (uint32_t i = 0; i < count; ++i) {
    Vec3 center{(rng.uniform() - 0.5f) * region.x, (rng.uniform() - 0.5f) * region.y,
                (rng.uniform() - 0.5f) * region.z};
    // Uniform direction on the sphere, then a uniform roll about it.
    float z = 1.0f - 2.0f * rng.uniform();
    float phi = 2.0f * kPi * rng.uniform();
    float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
    Vec3 n{r * std::cos(phi), r * std::sin(phi), z};
    Vec3 helper = std::fabs(n.y) < 0.99f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    Vec3 t0 = normalize(cross(helper, n));
    Vec3 b0 = cross(n, t0);
    float roll = 2.0f * kPi * rng.uniform();
    Vec3 u = t0 * std::cos(roll) + b0 * std::sin(roll);
    Vec3 v = cross(n, u);
    add_rect(m, center, u, v, card_size.x, card_size.y);
  }
  return m;
}

}  // namespace gib
