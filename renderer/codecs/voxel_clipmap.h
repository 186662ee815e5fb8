// The voxel-clipmap technique's GPU encodings on the CPU: toroidal addressing of its clipmap
// levels, level selection, the ambient-cube evaluation, the voxel opacity byte, the
// triangle/box overlap that voxelises geometry, the fill key and the nearest point of a
// triangle that scene_voxel_light lights a voxel at. Mirrors
// renderer/techniques/voxel_clipmap/include/vc_common.glsl and vc_voxelize.glsl;
// tests/test_voxel_clipmap.cpp checks that the two agree.
#pragma once
#include <array>
#include <cstdint>

namespace gib::codecs {

struct Int3 {
  int32_t x = 0, y = 0, z = 0;
  bool operator==(const Int3&) const = default;
};
struct Float3 {
  float x = 0, y = 0, z = 0;
};

// Non-negative remainder of g by n per axis: the slot world grid coordinate g occupies.
Int3 vc_wrap(Int3 g, int32_t n);
// Slot s of an n^3 grid as a linear index (x fastest, then y, then z).
uint32_t vc_slot_index(Int3 s, int32_t n);
// The world grid coordinate slot s holds in a box of n^3 starting at origin o.
Int3 vc_slot_world(Int3 s, Int3 o, int32_t n);
bool vc_in_box(Int3 g, Int3 o, int32_t n);
// Index of voxel g of level l in the atlas of levels of n^3 voxels.
uint32_t vc_voxel_index(uint32_t level, Int3 g, int32_t n);
// The box origin (grid units of `size`) centring an n-wide box on x.
Int3 vc_origin_around(Float3 x, float size, int32_t n);
// Finest level whose box (origins[l], n voxels of voxel_size x 2^l) holds x; `levels` when none.
uint32_t vc_voxel_level(Float3 x, const Int3* origins, uint32_t levels, float voxel_size, int32_t n);

// One cell's ambient cube: per axis (x, y, z) 14 floats: bounce +axis rgb, bounce -axis rgb, sky
// +axis rgb, sky -axis rgb, hit share +axis, -axis (voxel_clipmap_shared.h).
using AmbientAxis = std::array<float, 14>;
struct CubeValue {
  Float3 bounce, sky;
  float hit = 0;
};
// sum over axes of n_a^2 x the value of the direction on n's side (colours and hit share).
CubeValue vc_cube_eval(const AmbientAxis& x, const AmbientAxis& y, const AmbientAxis& z, Float3 n);

// The voxel opacity byte: opacity x 255 rounded half up, clamped to [1, 255] (0 is "no geometry").
uint32_t vc_opacity_byte(float opacity);

// Triangle a, b, c against the box of centre c and half extent h (separating axis theorem;
// touching counts as overlap).
bool vc_triangle_box_overlap(Float3 a, Float3 b, Float3 c, Float3 centre, Float3 h);

// scene_voxel_fill's per-voxel key (voxel_clipmap_shared.h): opacity byte in bits 24-31, bit 23
// the triangle faces the camera, triangle + 1 in bits 0-22 (0 when the id does not fit).
uint32_t vc_fill_key(uint32_t op8, bool facing, uint32_t triangle);

// A voxel's second triangle + 1 (0: none; voxel_clipmap_shared.h): bits 0-18 in y bits 13-31,
// bits 19-22 in w bits 23-26; the other bits of y and w are left as they are.
uint32_t vc_second_triangle(uint32_t y, uint32_t w);
void vc_set_second_triangle(uint32_t& y, uint32_t& w, uint32_t id);

// Barycentrics (u, v) of the point of triangle a, b, c nearest p (a (1 - u - v) + b u + c v);
// a degenerate triangle gives (0, 0).
struct Bary {
  float u = 0, v = 0;
};
Bary vc_closest_on_triangle(Float3 p, Float3 a, Float3 b, Float3 c);

// The cells' flood masks (irradiance_cell_vis, voxel_clipmap_shared.h). A window of 8^3 voxels is
// 64 rows (index z x 8 + y), bit x of a row for voxel x.
using VisRows = std::array<uint32_t, 64>;
// One flood step of one row: seeds, the row's reached voxels and its neighbouring rows' on the
// seed box's side (or-ed into `beside`), spread along the row through its free voxels away from
// the seed box (window x xlo..xhi).
uint32_t vc_vis_row_step(uint32_t free_row, uint32_t seed, uint32_t row, uint32_t beside, uint32_t xlo, uint32_t xhi);
// The relight's monotone flood from the seed box lo..hi (window coordinates, every voxel of it a
// seed): kVcVisSteps double-buffered steps over every row.
VisRows vc_vis_flood(const VisRows& free_rows, Int3 lo, Int3 hi);
// The stored mask (kVcCellVisWords words) of a flooded window: its middle 6^3 voxels.
std::array<uint32_t, 7> vc_vis_pack(const VisRows& reached);
// The mask bit of cell k holding voxel g (-1 outside the stored middle, voxels 2k - 2 .. 2k + 3).
int32_t vc_vis_bit(Int3 g, Int3 k);

}  // namespace gib::codecs
