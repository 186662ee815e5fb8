// Tangent-space normal maps (renderer/scene/normal_map.h, normal_map.glsl): the glTF convention
// on known answers (a flat quad mapped as glTF maps an image: +X of the map along increasing u,
// +Y up the image, i.e. along decreasing v), a mirrored mapping, the fallbacks, and the GPU
// against the CPU mirror on random frames.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/graph/executor.h"
#include "renderer/scene/gltf_export.h"
#include "renderer/scene/gltf_import.h"
#include "renderer/scene/normal_map.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/normal_map_test_shared.h"
#include "tests/technique_settings.h"
#include "tests/temp_dir.h"
#include "tests/test_rng.h"
#include "tests/texture_test_content.h"

namespace gib {
namespace {

using namespace normal_map_test;

// A unit quad in the z = 0 plane facing +z, its image upright: uv (0, 0) at the top left
// (x 0, y 1), u to the right, v down.
const Vec3 kP[3] = {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}};
const Vec2 kUpright[3] = {{0, 0}, {1, 0}, {0, 1}};
const Vec3 kUp{0, 0, 1};

void expect_vec(Vec3 a, Vec3 b, float tol = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(NormalMap, FlatTexelKeepsTheNormalExactly) {
  const Vec3 r = apply_normal_map(kUp, kP, kUpright, {0.5f, 0.5f, 1.0f}, 1.0f);
  EXPECT_EQ(r.x, 0.0f);
  EXPECT_EQ(r.y, 0.0f);
  EXPECT_EQ(r.z, 1.0f);
}

TEST(NormalMap, GltfConventionMapXAlongUAndYUpTheImage) {
  expect_vec(apply_normal_map(kUp, kP, kUpright, encode_tangent_normal({1, 0, 0}), 1.0f), {1, 0, 0});
  expect_vec(apply_normal_map(kUp, kP, kUpright, encode_tangent_normal({0, 1, 0}), 1.0f), {0, 1, 0});
  // 45 degrees towards +x: (1, 0, 1) / sqrt 2.
  const float h = std::sqrt(0.5f);
  expect_vec(apply_normal_map(kUp, kP, kUpright, encode_tangent_normal({h, 0, h}), 1.0f), {h, 0, h});
}

TEST(NormalMap, MirroredMappingFlipsTangentNotUp) {
  // u runs right to left: the map's +X points to -x, its +Y still up the image (+y).
  const Vec2 mirrored[3] = {{1, 0}, {0, 0}, {1, 1}};
  expect_vec(apply_normal_map(kUp, kP, mirrored, encode_tangent_normal({1, 0, 0}), 1.0f), {-1, 0, 0});
  expect_vec(apply_normal_map(kUp, kP, mirrored, encode_tangent_normal({0, 1, 0}), 1.0f), {0, 1, 0});
  // v runs bottom to top (the image upside down): +Y of the map points down.
  const Vec2 flipped[3] = {{0, 1}, {1, 1}, {0, 0}};
  expect_vec(apply_normal_map(kUp, kP, flipped, encode_tangent_normal({0, 1, 0}), 1.0f), {0, -1, 0});
}

TEST(NormalMap, ScaleScalesTheTangentialPart) {
  // m = (0.6, 0, 0.8) at scale 0.5: (0.3, 0, 0.8) normalised.
  const Vec3 texel = encode_tangent_normal({0.6f, 0.0f, 0.8f});
  const float l = std::sqrt(0.3f * 0.3f + 0.8f * 0.8f);
  expect_vec(apply_normal_map(kUp, kP, kUpright, texel, 0.5f), {0.3f / l, 0, 0.8f / l});
  expect_vec(apply_normal_map(kUp, kP, kUpright, texel, 0.0f), kUp);
}

TEST(NormalMap, DegenerateInputsKeepTheNormal) {
  const Vec2 same[3] = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
  const Vec3 texel = encode_tangent_normal({1, 0, 0});
  const Vec3 r = apply_normal_map(kUp, kP, same, texel, 1.0f);  // no uv area: no frame
  EXPECT_EQ(r.x, kUp.x);
  EXPECT_EQ(r.z, kUp.z);
  // A shading normal along the tangent: nothing of the tangent is left after orthogonalising.
  const Vec3 along{1, 0, 0};
  const Vec3 q = apply_normal_map(along, kP, kUpright, texel, 1.0f);
  EXPECT_EQ(q.x, 1.0f);
  EXPECT_EQ(q.y, 0.0f);
  // A texel that cancels the normal: m = (0, 0, -1) with n: r = -n, a unit vector (kept), and
  // m = 0 (texel 0.5 everywhere): no direction, the normal is kept.
  expect_vec(apply_normal_map(kUp, kP, kUpright, {0.5f, 0.5f, 0.5f}, 1.0f), kUp);
  const Vec3 nan{std::nanf(""), 0, 1};
  const Vec3 s = apply_normal_map(kUp, kP, kUpright, nan, 1.0f);
  EXPECT_EQ(s.z, 1.0f);
}

class NormalMapGpu : public test::GpuTest {};

TEST_F(NormalMapGpu, GpuMatchesCpuMirrorToAFewUlps) {
  test::Rng rng(18);
  std::vector<NormalMapTestQuery> q(8192);
  for (size_t i = 0; i < q.size(); ++i) {
    NormalMapTestQuery& x = q[i];
    Vec3 n = normalize({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    x.n[0] = n.x, x.n[1] = n.y, x.n[2] = n.z;
    x.scale = i % 7 == 0 ? 0.0f : rng.uniform(0.2f, 2.0f);
    const float span = i % 3 == 0 ? 1000.0f : 2.0f;  // far-from-origin triangles too
    for (float& p : x.p) p = rng.uniform(-span, span);
    for (float& t : x.t) t = rng.uniform(-3, 3);
    if (i % 11 == 0) x.t[2] = x.t[0], x.t[3] = x.t[1], x.t[4] = x.t[0], x.t[5] = x.t[1];  // no uv area
    for (float& c : x.texel) c = float(int(rng.uniform(0, 256))) / 255.0f;  // 8-bit texels
  }
  auto in = gpu().create_buffer(q.size() * sizeof(NormalMapTestQuery), BufferUsage::storage, "normal_map_test.queries");
  gpu().upload(*in, q.data(), q.size() * sizeof(NormalMapTestQuery));
  auto out = gpu().create_buffer(q.size() * sizeof(NormalMapTestOut), BufferUsage::storage, "normal_map_test.out");
  ComputePipelineDesc desc{"normal_map_test.comp",
                           {{NORMAL_MAP_TEST_BINDING_QUERIES, DescriptorKind::storage_buffer},
                            {NORMAL_MAP_TEST_BINDING_OUT, DescriptorKind::storage_buffer}},
                           sizeof(NormalMapTestPush)};
  auto pipeline = gpu().compute_pipeline(desc);
  const Bind binds[] = {{NORMAL_MAP_TEST_BINDING_QUERIES, in.get()}, {NORMAL_MAP_TEST_BINDING_OUT, out.get()}};
  const NormalMapTestPush push{uint32_t(q.size())};
  auto cmd = gpu().begin();
  cmd->bind(*pipeline, binds, &push, sizeof(push));
  cmd->dispatch((uint32_t(q.size()) + NORMAL_MAP_TEST_WORKGROUP_SIZE - 1) / NORMAL_MAP_TEST_WORKGROUP_SIZE);
  gpu().submit(std::move(cmd));
  std::vector<NormalMapTestOut> o(q.size());
  gpu().download(*out, o.data(), o.size() * sizeof(NormalMapTestOut));

  size_t bent = 0;
  float worst = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const NormalMapTestQuery& x = q[i];
    const Vec3 p[3] = {{x.p[0], x.p[1], x.p[2]}, {x.p[3], x.p[4], x.p[5]}, {x.p[6], x.p[7], x.p[8]}};
    const Vec2 t[3] = {{x.t[0], x.t[1]}, {x.t[2], x.t[3]}, {x.t[4], x.t[5]}};
    const Vec3 n{x.n[0], x.n[1], x.n[2]};
    const Vec3 c = apply_normal_map(n, p, t, {x.texel[0], x.texel[1], x.texel[2]}, x.scale);
    const Vec3 g{o[i].n[0], o[i].n[1], o[i].n[2]};
    const float d = std::fmax(std::fabs(c.x - g.x), std::fmax(std::fabs(c.y - g.y), std::fabs(c.z - g.z)));
    worst = std::fmax(worst, d);
    // sqrt and division on the GPU are within a few ulps (Vulkan's precision rules): 1e-5 is
    // ~80 ulps of 1, well above them and well below any visible change of a normal.
    EXPECT_LE(d, 1e-5f) << "query " << i;
    if (std::fabs(c.x - n.x) + std::fabs(c.y - n.y) + std::fabs(c.z - n.z) > 1e-3f) ++bent;
    if (::testing::Test::HasFailure()) break;
  }
  std::printf("normal maps: %zu queries, %zu bent, worst GPU-CPU difference %.3g\n", q.size(), bent, double(worst));
  EXPECT_GT(bent, q.size() / 2);  // the comparison is not of untouched normals
}

// The texel of a normal tilted 60 degrees towards +u, 8-bit: (238, 128, 191).
const uint8_t kTilted[4] = {238, 128, 191, 255};

// A 1 x 1 quad facing +z (uv = (x, 1 - y)), grey 0.5, whose normal map is a constant 4 x 4
// image of kTilted with normalTexture.scale `scale`.
std::vector<uint8_t> bumpy_quad(float scale) {
  std::vector<uint8_t> px;
  for (int i = 0; i < 16; ++i) px.insert(px.end(), kTilted, kTilted + 4);
  test::GltfContent g = test::textured_quad_content(test::tga(4, 4, px));
  g.doc["materials"] = {{{"name", "bumpy"},
                         {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}},
                         {"normalTexture", {{"index", 0}, {"scale", scale}}}}};
  return test::to_glb(g);
}

TEST(NormalMap, ImportReadsLinearNormalTextureAndScaleAndExportKeepsThem) {
  Scene s;
  const GltfImportReport r = import_gltf_bytes(s, bumpy_quad(0.75f), "bumpy.glb", ".", Mat4::identity());
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_FALSE(s.textures[0].srgb);  // normal maps are linear (glTF)
  EXPECT_EQ(r.texture_count, 1u);
  EXPECT_EQ(s.materials[0].normal_texture, 0);
  EXPECT_EQ(s.materials[0].normal_scale, 0.75f);
  EXPECT_EQ(s.materials[0].base_color_texture, -1);
  EXPECT_TRUE(s.features().has(Feature::textured));
  const FlatScene flat = flatten(s, 0);
  const GpuMaterial g = flat.materials[0];
  EXPECT_EQ(g.normal_texture, 0u);
  EXPECT_EQ(g.normal_scale, 0.75f);
  // Surface lookups read the material's normal texture only for instances flagged so.
  ASSERT_FALSE(flat.instances.empty());
  for (const GpuInstance& gi : flat.instances)
    EXPECT_EQ(gi.flags & kInstanceNormalMapped, flat.materials[gi.material].normal_texture != kTextureNone ? kInstanceNormalMapped : 0u);
  EXPECT_NE(flat.instances[0].flags & kInstanceNormalMapped, 0u);

  const test::TempDir dir("normal_map_roundtrip");
  const std::string path = (dir.path() / "bumpy.glb").string();
  export_gltf(s, path);
  Scene back;
  import_gltf(back, path, Mat4::identity());
  ASSERT_EQ(back.textures.size(), 1u);
  EXPECT_FALSE(back.textures[0].srgb);
  EXPECT_EQ(back.textures[0].mips, s.textures[0].mips);
  EXPECT_EQ(back.materials[0].normal_texture, 0);
  EXPECT_EQ(back.materials[0].normal_scale, 0.75f);
}

// End to end: the quad under a sun straight above it (+z) is lit by E cos(angle between the bent
// normal and the sun), in the G-buffer technique (`direct`) and in the path tracer's direct AOV
// alike. Analytic: albedo / pi * E * n'.z, n' the CPU mirror's bent normal (cos 60 deg = 0.5 for
// the unquantised texel).
class NormalMapRender : public test::GpuTest {
 protected:
  double mean_of(const Scene& scene, const std::string& technique, const std::string& aov, uint32_t frames) {
    const Technique& t = find_technique(technique);
    Settings s;
    s.width = 32;
    s.height = 32;
    s = apply_preset(t, technique == "reference" ? "ultra" : "medium", s);
    if (s.has_params<ReferenceSettings>()) ref(s).spp_per_frame = 16;
    Executor ex(gpu(), scene, s, make_passes(t), {aov});
    for (uint32_t f = 0; f < frames; ++f) ex.run_frame();
    const FloatImage img = ex.read(aov);
    double sum = 0;
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) sum += img.at(x, y, 1);
    return sum / (double(img.width) * img.height);
  }
};

TEST_F(NormalMapRender, BentNormalSetsTheSunsCosineInGbufferAndPathTracer) {
  const char* lit = R"({"materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [{"primitive": {"type": "box", "size": [1, 1, 1]}, "material": "grey",
                 "transform": {"translate": [100, 100, -50]}}],
    "sun": {"direction": [0, 0, 1], "irradiance": [3, 3, 3]},
    "camera": {"position": [0.5, 0.5, 2], "target": [0.5, 0.5, 0], "fov_y_deg": 20}})";
  const Vec3 z{0, 0, 1};
  const Vec3 p[3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  const Vec2 t[3] = {{0, 1}, {1, 1}, {1, 0}};
  for (float scale : {1.0f, 0.0f}) {
    Scene scene = parse_scene(nlohmann::json::parse(lit), "inline");
    import_gltf_bytes(scene, bumpy_quad(scale), "bumpy.glb", ".", Mat4::identity());
    const Vec3 texel{238 / 255.0f, 128 / 255.0f, 191 / 255.0f};
    const Vec3 bent = apply_normal_map(z, p, t, texel, scale);
    const double expect = 0.5 / M_PI * 3.0 * bent.z;
    const double g = mean_of(scene, "direct", find_technique("direct").output, 1);
    const double r = mean_of(scene, "reference", "direct", 2);
    std::printf("normal map scale %.0f: n'.z %.4f, analytic %.4f, direct technique %.4f, path tracer direct %.4f\n",
                double(scale), double(bent.z), expect, g, r);
    EXPECT_NEAR(g, expect, 0.01 * expect) << "scale " << scale;
    EXPECT_NEAR(r, expect, 0.01 * expect) << "scale " << scale;
  }
}

}  // namespace
}  // namespace gib
