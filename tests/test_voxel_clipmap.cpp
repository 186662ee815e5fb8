// The voxel-clipmap technique (renderer/techniques/voxel_clipmap/): its CPU mirror
// (renderer/codecs/voxel_clipmap.h) against known answers, and the GLSL it mirrors
// (vc_common.glsl, vc_voxelize.glsl via tests/voxel_clipmap_test.comp) against the CPU.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <vector>

#include "renderer/codecs/packed_float.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/codecs/voxel_clipmap.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap.h"
#include "tests/gpu_fixture.h"
#include "tests/voxel_clipmap_test_shared.h"

namespace gib {
namespace {

using namespace codecs;

TEST(VoxelClipmapCpu, ToroidalAddressingKnownAnswers) {
  EXPECT_EQ(vc_wrap({-1, -33, 65}, 32), (Int3{31, 31, 1}));
  EXPECT_EQ(vc_slot_index({1, 2, 3}, 32), 3u * 32 * 32 + 2u * 32 + 1u);
  EXPECT_EQ(vc_voxel_index(2, {-1, 0, 0}, 32), 2u * 32 * 32 * 32 + 31u);
  // A box scrolled by one voxel keeps every slot but one plane: the slot of the cell that left
  // now holds the cell that entered.
  const Int3 o{-16, -16, -16}, moved{-15, -16, -16};
  EXPECT_EQ(vc_slot_world({16, 0, 0}, o, 32), (Int3{-16, 0, 0}));  // -16 mod 32 = 16
  EXPECT_EQ(vc_slot_world(vc_wrap({-16, 3, 4}, 32), moved, 32), (Int3{16, 3, 4}));
  // Every slot maps to a distinct cell of the box, and back to itself.
  std::vector<int> seen(8 * 8 * 8, 0);
  for (int s = 0; s < 512; ++s) {
    const Int3 slot{s % 8, (s / 8) % 8, s / 64};
    const Int3 g = vc_slot_world(slot, {100, -7, 3}, 8);
    ASSERT_TRUE(vc_in_box(g, {100, -7, 3}, 8));
    ASSERT_EQ(vc_wrap(g, 8), slot);
    ++seen[vc_slot_index(vc_wrap(g, 8), 8)];
  }
  for (int c : seen) EXPECT_EQ(c, 1);
}

TEST(VoxelClipmapCpu, LevelSelectionNestsAroundTheCamera) {
  const Float3 cam{10000.3f, 1.7f, -2.2f};
  Int3 origins[4];
  for (uint32_t l = 0; l < 4; ++l) origins[l] = vc_origin_around(cam, 0.25f * float(1u << l), 32);
  EXPECT_EQ(vc_voxel_level(cam, origins, 4, 0.25f, 32), 0u);
  // Level 0 spans 8 m, level 1 16 m, level 3 64 m around the camera.
  EXPECT_EQ(vc_voxel_level({cam.x + 5.0f, cam.y, cam.z}, origins, 4, 0.25f, 32), 1u);
  EXPECT_EQ(vc_voxel_level({cam.x, cam.y + 20.0f, cam.z}, origins, 4, 0.25f, 32), 3u);
  EXPECT_EQ(vc_voxel_level({cam.x, cam.y, cam.z - 40.0f}, origins, 4, 0.25f, 32), 4u);
}

TEST(VoxelClipmapCpu, AmbientCubeKnownAnswers) {
  AmbientAxis x{}, y{}, z{};
  // Constant cube: every unit normal reads the constant (the squared components sum to 1).
  for (AmbientAxis* a : {&x, &y, &z})
    for (int i = 0; i < 14; ++i) (*a)[i] = i < 6 ? 0.5f : i < 12 ? 2.0f : 0.25f;
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  for (int i = 0; i < 1000; ++i) {
    Float3 n{g(rng), g(rng), g(rng)};
    const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = {n.x / len, n.y / len, n.z / len};
    const CubeValue v = vc_cube_eval(x, y, z, n);
    EXPECT_NEAR(v.bounce.x, 0.5f, 1e-6f);
    EXPECT_NEAR(v.sky.z, 2.0f, 4e-6f);
    EXPECT_NEAR(v.hit, 0.25f, 1e-6f);
  }
  // Axis normals read their own direction only: -y reads the -y bounce / sky entries.
  y = {0, 0, 0, 1, 2, 3, 0, 0, 0, 4, 5, 6, 0.5f, 0.75f};
  const CubeValue v = vc_cube_eval(x, y, z, {0, -1, 0});
  EXPECT_EQ(v.bounce.x, 1.0f);
  EXPECT_EQ(v.bounce.z, 3.0f);
  EXPECT_EQ(v.sky.y, 5.0f);
  EXPECT_EQ(v.hit, 0.75f);
}

TEST(VoxelClipmapCpu, TriangleBoxOverlapKnownAnswers) {
  const Float3 h{0.5f, 0.5f, 0.5f};
  // A wall in the plane z = 0.5 touches the box face: overlap (walls on boundaries fill both sides).
  EXPECT_TRUE(vc_triangle_box_overlap({-5, -5, 0.5f}, {5, -5, 0.5f}, {0, 5, 0.5f}, {0, 0, 0}, h));
  EXPECT_FALSE(vc_triangle_box_overlap({-5, -5, 0.51f}, {5, -5, 0.51f}, {0, 5, 0.51f}, {0, 0, 0}, h));
  // A triangle whose bounding box covers the box but whose hypotenuse passes beside its corner.
  EXPECT_FALSE(vc_triangle_box_overlap({0.6f, -2, 0}, {3, -2, 0}, {3, 0.4f, 0}, {0, 0, 0}, h));
  // A tiny triangle inside the box.
  EXPECT_TRUE(vc_triangle_box_overlap({0.1f, 0.1f, 0.1f}, {0.2f, 0.1f, 0.1f}, {0.1f, 0.2f, 0.1f}, {0, 0, 0}, h));
  EXPECT_EQ(vc_opacity_byte(0.0f), 1u);
  EXPECT_EQ(vc_opacity_byte(0.47f), 120u);  // 119.85 rounds to 120
  EXPECT_EQ(vc_opacity_byte(1.5f), 255u);
}

TEST(VoxelClipmapCpu, FillKeyKnownAnswers) {
  EXPECT_EQ(vc_fill_key(255, true, 0), 0xff800001u);
  EXPECT_EQ(vc_fill_key(1, false, 41), 0x0100002au);
  // Past 2^23 - 2 triangles no source triangle is kept (the voxel keeps its opacity).
  EXPECT_EQ(vc_fill_key(7, false, 0x7fffffu), 0x07000000u);
  // atomicMax order: opacity first, then facing the camera, then the larger triangle id.
  EXPECT_GT(vc_fill_key(200, false, 1), vc_fill_key(199, true, 5000000));
  EXPECT_GT(vc_fill_key(200, true, 1), vc_fill_key(200, false, 5000000));
}

TEST(VoxelClipmapCpu, SecondTriangleKnownAnswers) {
  uint32_t y = 0x1fffu, w = 0x7fffffu;  // every flag and opacity bit, the first triangle's field
  vc_set_second_triangle(y, w, 0x7ffffeu);
  EXPECT_EQ(y, 0xffffdfffu);
  EXPECT_EQ(w, 0x7ffffffu);
  EXPECT_EQ(vc_second_triangle(y, w), 0x7ffffeu);
  vc_set_second_triangle(y, w, 0);  // none: the other bits stay
  EXPECT_EQ(y, 0x1fffu);
  EXPECT_EQ(w, 0x7fffffu);
  y = 0x200u;
  w = 0x2au;
  vc_set_second_triangle(y, w, 0x80001u);
  EXPECT_EQ(y, 0x2200u);
  EXPECT_EQ(w, 0x80002au);
  EXPECT_EQ(vc_second_triangle(y, w), 0x80001u);
}

// The flood mask of the cube lookups' wall test: a wall of geometry voxels across the window
// (x = 4) keeps the flood on the seed's side; through a hole in it the flood goes on only away
// from the seed (monotone: not round the hole's edge and back).
TEST(VoxelClipmapCpu, VisFloodStopsAtWallsKnownAnswers) {
  VisRows free_rows, open, holed;
  open.fill(0xffu);
  const Int3 s{3, 3, 3};  // the seed: the cell's origin voxel (+x +y +z of cell (1, 1, 1))
  for (uint32_t row : vc_vis_flood(open, s, s)) ASSERT_EQ(row, 0xffu);  // open air: every voxel
  free_rows.fill(0xffu & ~(1u << 4));
  const VisRows walled = vc_vis_flood(free_rows, s, s);
  for (int r = 0; r < 64; ++r) ASSERT_EQ(walled[r], 0x0fu) << r;  // every voxel with x < 4, none past the wall
  holed = free_rows;
  holed[0] = 0xffu;  // the wall's voxel (4, 0, 0) is free
  const VisRows through = vc_vis_flood(holed, s, s);
  // Row 0 (y = z = 0, as far from the seed as rows go) past the hole; the other rows' voxels past
  // the wall only by coming back towards the seed: not reached.
  for (int r = 0; r < 64; ++r) ASSERT_EQ(through[r], r == 0 ? 0xffu : 0x0fu) << r;
  // Seeds on geometry voxels (a cell whose rays start at its centre: the box 3..4) are reached themselves.
  VisRows none{};
  const VisRows centre = vc_vis_flood(none, {3, 3, 3}, {4, 4, 4});
  EXPECT_EQ(centre[27], 0x18u);
  EXPECT_EQ(centre[36], 0x18u);
  EXPECT_EQ(centre[28 + 8], 0x18u);
  EXPECT_EQ(centre[26], 0u);
  // Monotone along x: from seed x 3 the free voxels 5..7 past geometry at 4 are not reached.
  EXPECT_EQ(vc_vis_row_step(0xefu, 0x08u, 0u, 0u, 3, 3), 0x0fu);
  EXPECT_EQ(vc_vis_row_step(0xffu, 0x08u, 0u, 0u, 3, 3), 0xffu);
  EXPECT_EQ(vc_vis_row_step(0xffu, 0u, 0u, 0x80u, 3, 3), 0x80u);  // from a row on the seed's side: onwards, not back
  // The stored middle: window voxels 1..6; cell k's voxels 2k - 2 .. 2k + 3.
  const std::array<uint32_t, 7> words = vc_vis_pack(walled);
  EXPECT_EQ(vc_vis_bit({0, 0, 0}, {1, 1, 1}), 0);
  EXPECT_EQ(vc_vis_bit({5, 5, 5}, {1, 1, 1}), 215);
  EXPECT_EQ(vc_vis_bit({-1, 0, 0}, {1, 1, 1}), -1);
  EXPECT_EQ(vc_vis_bit({6, 0, 0}, {1, 1, 1}), -1);
  // Cell (1, 1, 1)'s window starts at voxel -1: voxel 2 (window x 3) is reached, voxel 3 (the wall) not.
  const auto bit_set = [&](Int3 g) {
    const int32_t b = vc_vis_bit(g, {1, 1, 1});
    return ((words[b / 32] >> (b % 32)) & 1u) != 0;
  };
  EXPECT_TRUE(bit_set({2, 0, 5}));
  EXPECT_FALSE(bit_set({3, 0, 5}));
  EXPECT_FALSE(bit_set({4, 2, 1}));
}

TEST(VoxelClipmapCpu, ClosestPointOnTriangleKnownAnswers) {
  const Float3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  // Above the interior: the projection.
  Bary r = vc_closest_on_triangle({0.5f, 0.5f, 3}, a, b, c);
  EXPECT_NEAR(r.u, 0.25f, 1e-6f);
  EXPECT_NEAR(r.v, 0.25f, 1e-6f);
  // Beyond the hypotenuse: its midpoint (1, 1).
  r = vc_closest_on_triangle({2, 2, -1}, a, b, c);
  EXPECT_NEAR(r.u, 0.5f, 1e-6f);
  EXPECT_NEAR(r.v, 0.5f, 1e-6f);
  // Beyond vertex b along x: b itself.
  r = vc_closest_on_triangle({5, -1, 0}, a, b, c);
  EXPECT_NEAR(r.u, 1.0f, 1e-6f);
  EXPECT_NEAR(r.v, 0.0f, 1e-6f);
  // Below edge a-b: the foot on it.
  r = vc_closest_on_triangle({0.5f, -3, 0}, a, b, c);
  EXPECT_NEAR(r.u, 0.25f, 1e-6f);
  EXPECT_NEAR(r.v, 0.0f, 1e-6f);
  // Degenerate (collinear): the first vertex.
  r = vc_closest_on_triangle({1, 1, 1}, a, b, {4, 0, 0});
  EXPECT_EQ(r.u, 0.0f);
  EXPECT_EQ(r.v, 0.0f);
}

// ---------------------------------------------------------------- GPU agrees with the CPU
class VoxelClipmapGpu : public test::GpuTest {
 protected:
  static constexpr uint32_t kLevels = 4;
  static constexpr int32_t kN = 16;
  std::shared_ptr<Buffer> buffer(const void* data, uint64_t bytes, const char* name) {
    auto b = gpu().create_buffer(bytes, BufferUsage::storage, name);
    if (data) gpu().upload(*b, data, bytes);
    return b;
  }
  glsl::VcState state{};
  Int3 origins[kLevels];
  std::vector<AmbientAxis> cube[3];
  glsl::VcParams params() const {
    glsl::VcParams p{};
    p.grid = {uint32_t(kN), kLevels, 0, 0};
    p.sizes = {0.25f, 0.2f, 8.0f, 0.0f};
    return p;
  }
  void SetUp() override {
    test::GpuTest::SetUp();
    for (uint32_t l = 0; l < kLevels; ++l) {
      origins[l] = vc_origin_around({3.3f, -1.2f, 7.9f}, 0.25f * float(1u << l), kN);
      state.voxel_origin[l] = {origins[l].x, origins[l].y, origins[l].z, 1};
      state.cell_origin[l] = state.voxel_origin[l];
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 4.0f);
    for (auto& axis : cube) {
      axis.resize(64);
      for (auto& c : axis)
        for (float& f : c) f = u(rng);
    }
  }
  std::vector<glsl::VcTestOut> run(const std::vector<glsl::VcTestIn>& in, uint32_t mode) {
    using namespace glsl;
    const uint32_t count = uint32_t(in.size());
    auto st = buffer(&state, sizeof(state), "vc_test.state");
    std::shared_ptr<Buffer> axes[3];
    for (int a = 0; a < 3; ++a) axes[a] = buffer(cube[a].data(), cube[a].size() * sizeof(AmbientAxis), "vc_test.cube");
    std::vector<uint32_t> cells(64, kVcCellUpdated);
    auto cell_buf = buffer(cells.data(), cells.size() * 4, "vc_test.cells");
    auto in_buf = buffer(in.data(), in.size() * sizeof(VcTestIn), "vc_test.in");
    auto out_buf = buffer(nullptr, uint64_t(count) * sizeof(VcTestOut), "vc_test.out");
    ComputePipelineDesc desc{"voxel_clipmap_test.comp",
                             {{kVcTestBindState, DescriptorKind::storage_buffer},
                              {kVcTestBindX, DescriptorKind::storage_buffer},
                              {kVcTestBindY, DescriptorKind::storage_buffer},
                              {kVcTestBindZ, DescriptorKind::storage_buffer},
                              {kVcTestBindCells, DescriptorKind::storage_buffer},
                              {kVcTestBindIn, DescriptorKind::storage_buffer},
                              {kVcTestBindOut, DescriptorKind::storage_buffer}},
                             sizeof(VcTestPush)};
    auto pipeline = gpu().compute_pipeline(desc);
    const Bind binds[] = {{kVcTestBindState, st.get()},       {kVcTestBindX, axes[0].get()},
                          {kVcTestBindY, axes[1].get()},      {kVcTestBindZ, axes[2].get()},
                          {kVcTestBindCells, cell_buf.get()}, {kVcTestBindIn, in_buf.get()},
                          {kVcTestBindOut, out_buf.get()}};
    const VcTestPush push{params(), {mode, count, 0, 0}};
    auto cmd = gpu().begin();
    cmd->bind(*pipeline, binds, &push, sizeof(push));
    cmd->dispatch((count + kVcTestGroup - 1) / kVcTestGroup);
    gpu().submit(std::move(cmd));
    std::vector<VcTestOut> out(count);
    gpu().download(*out_buf, out.data(), out.size() * sizeof(VcTestOut));
    return out;
  }
};

float int_bits(int32_t i) { return std::bit_cast<float>(i); }

TEST_F(VoxelClipmapGpu, AddressingMatchesCpu) {
  std::mt19937 rng(9);
  std::uniform_int_distribution<int32_t> g(-100000, 100000), s(0, kN * kN * kN - 1), l(0, kLevels - 1);
  std::vector<glsl::VcTestIn> in(4096);
  for (auto& t : in) {
    t.a = {g(rng) % 50, g(rng), g(rng) % 7, l(rng)};
    t.p0 = {int_bits(g(rng)), int_bits(g(rng) % 20), int_bits(-g(rng)), int_bits(s(rng))};
  }
  in[0].a = {0, 0, 0, 0};  // inside the box below
  in[0].p0 = {int_bits(-3), int_bits(-3), int_bits(-3), int_bits(0)};
  const auto out = run(in, glsl::kVcTestAddressing);
  uint32_t inside = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const Int3 gi{in[i].a.x, in[i].a.y, in[i].a.z};
    const Int3 o{std::bit_cast<int32_t>(in[i].p0.x), std::bit_cast<int32_t>(in[i].p0.y), std::bit_cast<int32_t>(in[i].p0.z)};
    const int32_t slot = std::bit_cast<int32_t>(in[i].p0.w);
    ASSERT_EQ(out[i].u.x, vc_voxel_index(uint32_t(in[i].a.w), gi, kN)) << i;
    ASSERT_EQ(out[i].u.y, vc_slot_index(vc_wrap(gi, kN), kN)) << i;
    ASSERT_EQ(out[i].u.z, vc_in_box(gi, o, kN) ? 1u : 0u) << i;
    const Int3 w = vc_slot_world({slot % kN, (slot / kN) % kN, slot / (kN * kN)}, o, kN);
    ASSERT_EQ((Int3{out[i].i.x, out[i].i.y, out[i].i.z}), w) << i;
    inside += out[i].u.z;
  }
  EXPECT_GE(inside, 1u);
}

TEST_F(VoxelClipmapGpu, LevelSelectionMatchesCpu) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-12.0f, 18.0f);
  std::vector<glsl::VcTestIn> in(4096);
  for (auto& t : in) t.p0 = {u(rng), u(rng), u(rng), 0};
  const auto out = run(in, glsl::kVcTestLevel);
  uint32_t per_level[kLevels + 1] = {}, skipped = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const Float3 x{in[i].p0.x, in[i].p0.y, in[i].p0.z};
    // A point within float error of a voxel boundary may fall either side on a device whose
    // division is not correctly rounded (Vulkan allows 2.5 ulp): skipped.
    bool near = false;
    for (uint32_t l = 0; l < kLevels; ++l)
      for (float c : {x.x, x.y, x.z}) {
        const double q = double(c) / (0.25 * double(1u << l));
        near = near || std::fabs(q - std::round(q)) < 1e-4;
      }
    if (near) { ++skipped; continue; }
    const uint32_t l = vc_voxel_level(x, origins, kLevels, 0.25f, kN);
    ASSERT_EQ(out[i].u.x, l) << i;
    const Int3 o = vc_origin_around(x, 0.5f, kN);
    ASSERT_EQ((Int3{out[i].i.x, out[i].i.y, out[i].i.z}), o) << i;
    ++per_level[l];
  }
  for (uint32_t l = 0; l <= kLevels; ++l) EXPECT_GT(per_level[l], 0u) << "level " << l;
  EXPECT_LT(skipped, 64u);
}

TEST_F(VoxelClipmapGpu, AmbientCubeMatchesCpu) {
  std::mt19937 rng(13);
  std::normal_distribution<float> g;
  std::vector<glsl::VcTestIn> in(2048);
  for (size_t i = 0; i < in.size(); ++i) {
    Float3 n{g(rng), g(rng), g(rng)};
    const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    in[i].a = {int32_t(i % 64), 0, 0, 0};
    in[i].p0 = {n.x / len, n.y / len, n.z / len, 0};
  }
  in[0].p0 = {0.0f, -1.0f, 0.0f, 0.0f};
  const auto out = run(in, glsl::kVcTestCube);
  for (size_t i = 0; i < in.size(); ++i) {
    const size_t c = size_t(in[i].a.x);
    const CubeValue v = vc_cube_eval(cube[0][c], cube[1][c], cube[2][c], {in[i].p0.x, in[i].p0.y, in[i].p0.z});
    // Three products summed: the device may fuse them (1 ulp each at values below 4).
    ASSERT_NEAR(out[i].f0.x, v.bounce.x, 4e-6f) << i;
    ASSERT_NEAR(out[i].f0.z, v.bounce.z, 4e-6f) << i;
    ASSERT_NEAR(out[i].f1.y, v.sky.y, 4e-6f) << i;
    ASSERT_NEAR(out[i].f0.w, v.hit, 4e-6f) << i;
  }
  EXPECT_EQ(out[0].f0.y, cube[1][0][4]);  // -y reads the -y bounce entry exactly
}

TEST_F(VoxelClipmapGpu, VoxelizationAndOpacityMatchCpu) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f), o(-0.2f, 1.2f);
  std::vector<glsl::VcTestIn> in(8192);
  for (auto& t : in) {
    t.p0 = {u(rng), u(rng), u(rng), o(rng)};
    t.p1 = {u(rng), u(rng), u(rng), 0};
    t.p2 = {u(rng), u(rng), u(rng), 0};
    t.p3 = {u(rng) * 0.3f, u(rng) * 0.3f, u(rng) * 0.3f, 0.25f};
  }
  const auto overlap = run(in, glsl::kVcTestOverlap);
  const auto opacity = run(in, glsl::kVcTestOpacity);
  uint32_t hits = 0, misses = 0, differ = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const auto& t = in[i];
    const bool cpu = vc_triangle_box_overlap({t.p0.x, t.p0.y, t.p0.z}, {t.p1.x, t.p1.y, t.p1.z},
                                             {t.p2.x, t.p2.y, t.p2.z}, {t.p3.x, t.p3.y, t.p3.z},
                                             {t.p3.w, t.p3.w, t.p3.w});
    // Random triangles almost never graze the box to within float error; count any that do.
    differ += (overlap[i].u.x != 0u) != cpu;
    (cpu ? hits : misses) += 1;
    ASSERT_EQ(opacity[i].u.x, vc_opacity_byte(t.p0.w)) << i;
  }
  EXPECT_LE(differ, 2u);
  EXPECT_GT(hits, 500u);
  EXPECT_GT(misses, 500u);
}

TEST_F(VoxelClipmapGpu, FillKeyAndClosestPointMatchCpu) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  std::uniform_int_distribution<int32_t> byte(1, 255), id(0, 0x800010);
  std::vector<glsl::VcTestIn> in(4096);
  for (auto& t : in) {
    t.a = {byte(rng), byte(rng) & 1, id(rng), 0};
    t.p0 = {u(rng), u(rng), u(rng), 0};
    t.p1 = {u(rng), u(rng), u(rng), 0};
    t.p2 = {u(rng), u(rng), u(rng), 0};
    t.p3 = {u(rng), u(rng), u(rng), 0};
  }
  const auto key = run(in, glsl::kVcTestFillKey);
  const auto closest = run(in, glsl::kVcTestClosest);
  uint32_t inside = 0, differ = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const auto& t = in[i];
    ASSERT_EQ(key[i].u.x, vc_fill_key(uint32_t(t.a.x), t.a.y != 0, uint32_t(t.a.z))) << i;
    const Bary cpu = vc_closest_on_triangle({t.p3.x, t.p3.y, t.p3.z}, {t.p0.x, t.p0.y, t.p0.z},
                                            {t.p1.x, t.p1.y, t.p1.z}, {t.p2.x, t.p2.y, t.p2.z});
    // Nearly degenerate random triangles are ill-conditioned in float; count any that differ.
    differ += std::abs(closest[i].f0.x - cpu.u) > 1e-3f || std::abs(closest[i].f0.y - cpu.v) > 1e-3f;
    inside += cpu.u > 0.0f && cpu.v > 0.0f && cpu.u + cpu.v < 1.0f;
  }
  EXPECT_LE(differ, 2u);
  EXPECT_GT(inside, 200u);  // both branches (interior and edges) are exercised
}

TEST_F(VoxelClipmapGpu, SecondTriangleMatchesCpu) {
  std::mt19937 rng(31);
  std::uniform_int_distribution<uint32_t> word, id(0, 0x7fffff);
  std::vector<glsl::VcTestIn> in(1024);
  for (auto& t : in) t.a = {int32_t(word(rng)), int32_t(word(rng)), int32_t(id(rng)), 0};
  const auto out = run(in, glsl::kVcTestSecond);
  for (size_t i = 0; i < in.size(); ++i) {
    uint32_t y = uint32_t(in[i].a.x), w = uint32_t(in[i].a.y);
    ASSERT_EQ(out[i].u.x, vc_second_triangle(y, w)) << i;
    vc_set_second_triangle(y, w, uint32_t(in[i].a.z));
    ASSERT_EQ(out[i].u.y, y) << i;
    ASSERT_EQ(out[i].u.z, w) << i;
    ASSERT_EQ(out[i].u.w, uint32_t(in[i].a.z)) << i;
  }
}

TEST_F(VoxelClipmapGpu, VisFloodStepAndBitMatchCpu) {
  std::mt19937 rng(37);
  std::uniform_int_distribution<uint32_t> row(0, 255);
  std::uniform_int_distribution<int32_t> g(-40, 40);
  std::vector<glsl::VcTestIn> in(4096);
  std::uniform_int_distribution<int32_t> x(0, 7);
  for (auto& t : in) {
    t.a = {int32_t(row(rng)), int32_t(row(rng) & row(rng) & row(rng)), int32_t(row(rng)), int32_t(row(rng))};
    const int32_t lo = x(rng), hi = std::min(7, lo + x(rng) % 2);
    t.p0 = {int_bits(lo), int_bits(hi), 0, 0};
  }
  const auto step = run(in, glsl::kVcTestVisStep);
  for (size_t i = 0; i < in.size(); ++i)
    ASSERT_EQ(step[i].u.x, vc_vis_row_step(uint32_t(in[i].a.x), uint32_t(in[i].a.y), uint32_t(in[i].a.z),
                                           uint32_t(in[i].a.w), uint32_t(std::bit_cast<int32_t>(in[i].p0.x)),
                                           uint32_t(std::bit_cast<int32_t>(in[i].p0.y))))
        << i;
  uint32_t stored = 0;
  for (auto& t : in) {
    const int32_t kx = g(rng) / 2, ky = g(rng) / 2, kz = g(rng) / 2;
    t.a = {2 * kx + g(rng) % 5, 2 * ky + g(rng) % 5, 2 * kz + g(rng) % 5, 0};
    t.p0 = {int_bits(kx), int_bits(ky), int_bits(kz), 0};
  }
  const auto bit = run(in, glsl::kVcTestVisBit);
  for (size_t i = 0; i < in.size(); ++i) {
    const Int3 k{std::bit_cast<int32_t>(in[i].p0.x), std::bit_cast<int32_t>(in[i].p0.y), std::bit_cast<int32_t>(in[i].p0.z)};
    ASSERT_EQ(bit[i].i.x, vc_vis_bit({in[i].a.x, in[i].a.y, in[i].a.z}, k)) << i;
    stored += bit[i].i.x >= 0;
  }
  EXPECT_GT(stored, 100u);
}

// ---------------------------------------------------------------- the plan
// scene_voxel_light exists for geometry_light: with it off the graph culls the pass (it would
// dispatch and return), with it on the pass runs.
TEST(VoxelClipmapPlan, SceneVoxelLightRunsOnlyWithGeometryLight) {
  const Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/closed_box.json");
  const Technique& t = find_technique("voxel-clipmap");
  auto light_pass = [&](double on) {
    Settings s = apply_options(t, apply_preset(t, "medium", Settings{}), {{"geometry_light", on}});
    s.width = 64;
    s.height = 36;
    std::vector<PassDecl> decls;
    for (auto& pass : make_passes(t)) decls.push_back(pass->declare(scene, s));
    const Plan plan = compile(decls, {scene.features(), {t.output}, s.width, s.height});
    for (const PlannedPass& pp : plan.passes)
      if (pp.name == "scene_voxel_light") return pp;
    ADD_FAILURE() << "no scene_voxel_light in the plan";
    return PlannedPass{};
  };
  const PlannedPass off = light_pass(0), on = light_pass(1);
  EXPECT_FALSE(off.runs);
  EXPECT_EQ(off.reason, "switched off: geometry_light is 0");
  EXPECT_TRUE(on.runs) << on.reason;
}

// ---------------------------------------------------------------- energy through the clipmap
// The closed box (cases/scenes/closed_box.json: a 4 m box, walls of albedo 0.99 emitting 0.01,
// no sun or sky; the exact radiance E / (1 - a) = 1 needs hundreds of bounces) at the stage
// level, with geometry_light and every voxel and cell refreshed each frame. Each stage of the
// loop gets a known input through a graph override and must pass the light on undiminished:
// cubes B everywhere inside -> every wall voxel reflects a (e + B); wall voxels of radiance R
// -> every cell inside sees R in every direction (and the walls' emission e as its direct
// part). A loss of x per bounce caps the box at e / (1 - a (1 - x)): 2 % caps it at 0.34.
constexpr float kBoxAlbedo = 0.99f, kBoxEmission = 0.01f;

bool vc_in_closed_box(float x, float y, float z) { return x > -2 && x < 2 && y > 0 && y < 4 && z > -2 && z < 2; }

class VoxelClipmapEnergy : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    scene_ = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/closed_box.json");
    const Technique& t = find_technique("voxel-clipmap");
    Settings s;
    s.width = 64;
    s.height = 36;
    settings_ = apply_options(t, apply_preset(t, "medium", s),
                              {{"geometry_light", 1}, {"feed_weight", 1}, {"history_frames", 1}, {"lit_voxels", 1e7},
                               {"queue_a", 65536}, {"queue_a_new", 65536}, {"queue_b", 65536}});
  }
  std::unique_ptr<Executor> executor() {
    const Technique& t = find_technique("voxel-clipmap");
    return std::make_unique<Executor>(gpu(), scene_, settings_, make_passes(t), std::vector<std::string>{"final_color"});
  }
  const VoxelClipmapSettings& p() const { return settings_.params<VoxelClipmapSettings>(); }
  static glsl::VcState state(Executor& ex) {
    glsl::VcState st{};
    const auto bytes = ex.read_buffer("voxel_clip_state");
    std::memcpy(&st, bytes.data(), sizeof(st));
    return st;
  }
  // Level-0 voxels whose centre lies inside the box and that hold geometry (the walls' inner layer).
  template <class F>
  void for_inner_wall_voxels(const glsl::VcState& st, const std::vector<uint32_t>& vox, F f) const {
    const int32_t n = int32_t(p().grid);
    const float vs = p().voxel_size;
    const Int3 o{st.voxel_origin[0].x, st.voxel_origin[0].y, st.voxel_origin[0].z};
    for (int32_t z = o.z; z < o.z + n; ++z)
      for (int32_t y = o.y; y < o.y + n; ++y)
        for (int32_t x = o.x; x < o.x + n; ++x) {
          if (!vc_in_closed_box((x + 0.5f) * vs, (y + 0.5f) * vs, (z + 0.5f) * vs)) continue;
          const uint32_t idx = vc_voxel_index(0, {x, y, z}, n);
          if ((vox[idx * 4 + 1] & glsl::kVcVoxelGeometry) != 0) f(idx);
        }
  }
  // Every level's cells with the centre inside the box (and not on its walls' voxel layer).
  template <class F>
  void for_inner_cells(const glsl::VcState& st, F f) const {
    const int32_t m = int32_t(p().grid) / 2;
    for (uint32_t l = 0; l < p().levels; ++l) {
      const float c = 2 * p().voxel_size * float(1u << l);
      const Int3 o{st.cell_origin[l].x, st.cell_origin[l].y, st.cell_origin[l].z};
      for (int32_t z = o.z; z < o.z + m; ++z)
        for (int32_t y = o.y; y < o.y + m; ++y)
          for (int32_t x = o.x; x < o.x + m; ++x)
            if (vc_in_closed_box((x + 0.5f) * c, (y + 0.5f) * c, (z + 0.5f) * c))
              f(l, uint32_t(l * m * m * m + vc_slot_index(vc_wrap({x, y, z}, m), m)));
    }
  }
  Scene scene_;
  Settings settings_;
};

std::vector<uint32_t> as_words(const std::vector<uint8_t>& b) {
  std::vector<uint32_t> w(b.size() / 4);
  std::memcpy(w.data(), b.data(), w.size() * 4);
  return w;
}
template <class T>
std::vector<uint8_t> as_bytes(const std::vector<T>& v) {
  std::vector<uint8_t> b(v.size() * sizeof(T));
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

TEST_F(VoxelClipmapEnergy, VoxelsReflectAlbedoTimesTheCubes) {
  auto ex = executor();
  ex->run_frame();
  // Cubes: bounce B in every direction and the walls' emission as the direct part, in every cell
  // inside the box; cells outside see nothing (a converged box's outside is dark).
  const float B = 0.5f;
  std::vector<float> cube(ex->read_buffer("irradiance_x").size() / 4, 0.0f);
  for_inner_cells(state(*ex), [&](uint32_t, uint32_t cell) {
    const uint32_t at = cell * glsl::kVcCellFloats;
    for (int f = 0; f < 6; ++f) cube[at + f] = B;
    for (int f = 6; f < 12; ++f) cube[at + f] = kBoxEmission;
    for (int f = 12; f < 14; ++f) cube[at + f] = 1.0f;  // every ray meets the walls
  });
  for (const char* axis : {"irradiance_x", "irradiance_y", "irradiance_z"})
    ex->add_override({"irradiance_relight", axis, as_bytes(cube)});
  for (int f = 0; f < 3; ++f) ex->run_frame();
  const auto vox = as_words(ex->read_buffer("scene_voxel_data"));
  // Fed voxels: direct_light (the walls' emission through the pixel's sky rays: a e) + a B; lit
  // ones: a (B + e) from the cubes. Both a (e + B).
  const double want = double(kBoxAlbedo) * (kBoxEmission + B);
  double sum = 0, worst = 1, sum_fed = 0;
  uint32_t count = 0, fed = 0, dark = 0;
  for_inner_wall_voxels(state(*ex), vox, [&](uint32_t idx) {
    float rgb[3];
    decode_rgb9e5(vox[idx * 4], rgb);
    const double r = rgb[1] / want;
    sum += r;
    worst = std::min(worst, r);
    ++count;
    dark += r < 0.05;
    if (r < 0.95 && std::getenv("GIB_VC_ENERGY_VERBOSE")) {
      const int32_t n = int32_t(p().grid);
      const uint32_t slot = idx % uint32_t(n * n * n);
      const glsl::VcState st = state(*ex);
      const Int3 g = vc_slot_world({int32_t(slot) % n, (int32_t(slot) / n) % n, int32_t(slot) / (n * n)},
                                   {st.voxel_origin[0].x, st.voxel_origin[0].y, st.voxel_origin[0].z}, n);
      std::printf("  voxel below 0.95: %d %d %d flags %x r %.4f\n", g.x, g.y, g.z, vox[idx * 4 + 1], r);
    }
    if ((vox[idx * 4 + 1] & glsl::kVcVoxelFed) != 0) {
      ++fed;
      sum_fed += r;
    }
  });
  ASSERT_GT(count, 500u);
  ASSERT_GT(fed, 100u);
  std::printf("voxels: %u inner wall voxels: mean %.4f, worst %.4f of a (e + B); %u fed: mean %.4f; %u lit: mean %.4f; %u dark\n",
              count, sum / count, worst, fed, sum_fed / fed, count - fed, (sum - sum_fed) / std::max(1u, count - fed), dark);
  // A loss-free stage gives 1 for every voxel. Measured (lavapipe, medium): pixel-fed voxels
  // 0.9997, voxels lit from their triangle 1.0001, worst voxel 0.998. Voxels on a room's edges
  // and corners hold two or three walls; with one triangle kept per voxel the wall test missed
  // the others and the lookup blended in cells outside the room (lit mean 0.973, edges about
  // 0.78); the fill now keeps one per dominant normal axis. GIB_VC_ENERGY_VERBOSE=1 lists voxels
  // below 0.95.
  EXPECT_GT(sum_fed / fed, 0.998) << "pixel-fed voxels";
  EXPECT_GT((sum - sum_fed) / std::max(1u, count - fed), 0.995) << "voxels lit from their triangle";
  EXPECT_GT(worst, 0.99) << "worst voxel (a room's edges and corners)";
  EXPECT_GT(sum / count, 0.98) << "light lost from the cubes to the voxels per bounce";
  EXPECT_LT(sum / count, 1.005) << "light gained from the cubes to the voxels per bounce";
}

TEST_F(VoxelClipmapEnergy, CubesSeeTheWallsRadiance) {
  auto ex = executor();
  ex->run_frame();
  // Voxels: every voxel with geometry reflects R and emits e.
  const float R = 0.5f;
  auto vox = as_words(ex->read_buffer("scene_voxel_data"));
  for (size_t i = 0; i < vox.size() / 4; ++i)
    if (vox[i * 4 + 1] & glsl::kVcVoxelGeometry) {
      vox[i * 4] = encode_rgb9e5(R, R, R);
      vox[i * 4 + 2] = encode_rgb9e5(kBoxEmission, kBoxEmission, kBoxEmission);
    }
  ex->add_override({"scene_voxel_light", "scene_voxel_data", as_bytes(vox)});
  for (int f = 0; f < 3; ++f) ex->run_frame();
  // Every voxel a pixel gave opacity holds voxelised geometry (and so the injected R): the fill
  // reaches the voxels on both sides of a wall on a voxel boundary, the far walls' inner ones too.
  {
    const auto v2 = as_words(ex->read_buffer("scene_voxel_data"));
    uint32_t without_geometry = 0;
    for (size_t i = 0; i < v2.size() / 4; ++i)
      without_geometry += (v2[i * 4 + 1] & glsl::kVcOpacityMask) != 0 && (v2[i * 4 + 1] & glsl::kVcVoxelGeometry) == 0;
    EXPECT_EQ(without_geometry, 0u) << "voxels with opacity but no voxelised geometry";
  }
  const auto cx = ex->read_buffer("irradiance_x"), cy = ex->read_buffer("irradiance_y"), cz = ex->read_buffer("irradiance_z");
  const float* axes[3] = {reinterpret_cast<const float*>(cx.data()), reinterpret_cast<const float*>(cy.data()),
                          reinterpret_cast<const float*>(cz.data())};
  float r_packed[3];
  decode_rgb9e5(encode_rgb9e5(R, R, R), r_packed);
  const auto cs = as_words(ex->read_buffer("irradiance_cell_state"));
  double sum = 0, worst = 1, direct = 0, hits = 0;
  uint32_t count = 0;
  for_inner_cells(state(*ex), [&](uint32_t l, uint32_t cell) {
    if (l > 0) return;  // coarser cells' boxes reach past the walls
    // Only cells relit in the last frame (age 0): the others still hold what they saw before.
    if ((cs[cell] & glsl::kVcCellRelit) == 0 || (cs[cell] & glsl::kVcAgeMask) != 0) return;
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 2; ++d) {
        const double b = axes[a][cell * glsl::kVcCellFloats + d * 3 + 1] / r_packed[1];
        sum += b;
        worst = std::min(worst, b);
        direct += axes[a][cell * glsl::kVcCellFloats + 6 + d * 3 + 1] / kBoxEmission;
        hits += axes[a][cell * glsl::kVcCellFloats + 12 + d];
        ++count;
      }
  });
  ASSERT_GT(count, 1000u);
  std::printf("cubes: %u cell directions: bounce mean %.4f, worst %.4f of R; direct mean %.4f of e; hit share %.4f\n",
              count, sum / count, worst, direct / count, hits / count);
  // Loss-free: every direction of every cell sees R (measured 1.0000 on lavapipe, medium).
  EXPECT_NEAR(sum / count, 1.0, 0.002) << "light lost or gained from the voxels to the cubes per bounce";
  EXPECT_NEAR(direct / count, 1.0, 0.01);
  // Inside a closed box every ray meets a wall: the hit share the pixels' bounce is divided by is 1.
  EXPECT_NEAR(hits / count, 1.0, 0.01);
}

}  // namespace
}  // namespace gib
