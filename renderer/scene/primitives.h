// Procedural meshes with per-vertex normals and UVs. Every mesh is centred on the origin and
// wound counter-clockwise seen from the side its normals point to, but nothing downstream
// culls: a quad or a leaf card is visible (and hit by rays) from both sides.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include "renderer/scene/math.h"
#include "renderer/scene/scene.h"

namespace gib {

// Which way a flat primitive (quad, thin slab) faces. Each facing has a fixed in-plane frame
// (tangent = +U direction, bitangent = +V direction, tangent x bitangent = normal):
//   +y: U = +x, V = -z   (floor)        -y: U = +x, V = +z   (ceiling)
//   +z: U = +x, V = +y   (back wall)    -z: U = -x, V = +y
//   +x: U = -z, V = +y                  -x: U = +z, V = +y
// size.x is measured along U and size.y along V.
enum class Facing : uint32_t { pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };
std::optional<Facing> parse_facing(std::string_view s);  // "+x", "-x", ... "+z", "-z"
std::string_view facing_name(Facing f);
Vec3 facing_normal(Facing f);

// Axis-aligned box; 24 vertices (hard edges), 12 triangles.
Mesh make_box(Vec3 size);
// One rectangle; 4 vertices, 2 triangles; UVs span [0,1]^2.
Mesh make_quad(Vec2 size, Facing facing = Facing::pos_y);
// UV sphere around +Y: `segments` slices around, max(2, segments/2) rings;
// 2 * segments * (rings - 1) triangles (no degenerate triangles at the poles).
Mesh make_sphere(float radius, uint32_t segments);
// Cylinder along Y from -height/2 to +height/2; 2 * segments side triangles plus
// segments per cap when capped (caps have their own flat-normal vertices).
Mesh make_cylinder(float radius, float height, uint32_t segments, bool capped);
// A box that is `thickness` thick along the facing axis and size.x by size.y in the plane:
// a wall with two real faces (and thin edges) rather than a single-sided quad.
Mesh make_thin_slab(Vec2 size, float thickness = 0.02f, Facing facing = Facing::pos_z);
// `count` randomly placed and oriented quad cards (2 triangles each, UVs [0,1]^2 for
// leaf masks) whose centres are uniform in a box of `region` centred on the origin.
// Deterministic: the same seed gives bit-identical geometry on every platform.
Mesh make_leaf_cards(uint32_t count, Vec3 region, Vec2 card_size, uint32_t seed);

}  // namespace gib
