// Scene module: math, primitives, feature derivation, loader errors, flatten, sample scenes.
#include <gtest/gtest.h>

#include <functional>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>

#include "renderer/scene/features.h"
#include "renderer/scene/math.h"
#include "renderer/scene/primitives.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

using json = nlohmann::json;
constexpr float kPi = std::numbers::pi_v<float>;

std::string scene_path(const std::string& name) { return std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + name; }

void expect_near(Vec3 a, Vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// ---------------------------------------------------------------- math

TEST(SceneMath, InverseTimesMatrixIsIdentity) {
  Mat4 mats[] = {Mat4::trs({1, -2, 3}, {30, 45, -60}, {2, 0.5f, 3}),
                 Mat4::trs({1e4f, 0, -1e4f}, {0, 90, 0}, {-1, 1, 1}),
                 Mat4::perspective(1.0f, 1.5f, 0.1f, 100.0f),
                 Mat4::look_at({3, 4, 5}, {0, 1, 0}, {0, 1, 0})};
  for (const Mat4& m : mats) {
    Mat4 p = m.inverse() * m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(p.m[c][r], c == r ? 1.0f : 0.0f, 2e-4f);
  }
}

TEST(SceneMath, SingularInverseIsZeroNotNaN) {
  Mat4 inv = Mat4::scaling({0, 1, 1}).inverse();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_EQ(inv.m[c][r], 0.0f);
}

TEST(SceneMath, TransposeSwapsRowsAndColumns) {
  Mat4 m = Mat4::trs({1, 2, 3}, {10, 20, 30}, {1, 2, 3});
  Mat4 t = m.transpose();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_EQ(t.m[c][r], m.m[r][c]);
}

TEST(SceneMath, RotationsAreRightHanded) {
  expect_near(Mat4::rotation_z(kPi / 2).transform_vector({1, 0, 0}), {0, 1, 0});
  expect_near(Mat4::rotation_x(kPi / 2).transform_vector({0, 1, 0}), {0, 0, 1});
  expect_near(Mat4::rotation_y(kPi / 2).transform_vector({0, 0, 1}), {1, 0, 0});
}

TEST(SceneMath, TrsAppliesScaleThenRzRyRxThenTranslation) {
  Vec3 t{1, 2, 3}, r{30, -45, 60}, s{2, 3, 4};
  Vec3 p{0.3f, -0.7f, 1.1f};
  constexpr float d = kPi / 180.0f;
  Vec3 expected = Mat4::translation(t).transform_point(Mat4::rotation_x(r.x * d).transform_point(
      Mat4::rotation_y(r.y * d).transform_point(Mat4::rotation_z(r.z * d).transform_point(Mat4::scaling(s).transform_point(p)))));
  expect_near(Mat4::trs(t, r, s).transform_point(p), expected);
}

TEST(SceneMath, PerspectiveMapsNearFarToZeroOneAndFlipsY) {
  float n = 0.1f, f = 50.0f;
  Mat4 p = Mat4::perspective(kPi / 3, 16.0f / 9.0f, n, f);
  Vec4 a = p.transform({0, 0, -n, 1});
  Vec4 b = p.transform({0, 0, -f, 1});
  EXPECT_NEAR(a.z / a.w, 0.0f, 1e-6f);
  EXPECT_NEAR(b.z / b.w, 1.0f, 1e-5f);
  // A point above the axis lands in the upper half of the image: negative NDC y in Vulkan.
  Vec4 up = p.transform({0, 1, -5, 1});
  EXPECT_LT(up.y / up.w, 0.0f);
  // The top edge of the frustum is exactly y = -1.
  Vec4 top = p.transform({0, std::tan(kPi / 6) * 5.0f, -5, 1});
  EXPECT_NEAR(top.y / top.w, -1.0f, 1e-5f);
  Vec4 right = p.transform({std::tan(kPi / 6) * 5.0f * 16.0f / 9.0f, 0, -5, 1});
  EXPECT_NEAR(right.x / right.w, 1.0f, 1e-5f);
}

TEST(SceneMath, LookAtPutsTargetOnMinusZ) {
  Vec3 eye{3, 4, 5}, target{0, 1, 0};
  Mat4 v = Mat4::look_at(eye, target, {0, 1, 0});
  expect_near(v.transform_point(eye), {0, 0, 0});
  Vec3 t = v.transform_point(target);
  expect_near(t, {0, 0, -length(target - eye)}, 1e-4f);
  // World up stays in the upper half of the view.
  EXPECT_GT(v.transform_vector({0, 1, 0}).y, 0.0f);
  // World +x is to the right for a camera on +z looking at the origin.
  Mat4 v2 = Mat4::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  expect_near(v2.transform_vector({1, 0, 0}), {1, 0, 0});
}

TEST(SceneMath, LookAtStraightDownStaysFinite) {
  Mat4 v = Mat4::look_at({0, 10, 0}, {0, 0, 0}, {0, 1, 0});
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(v.m[c][r]));
  expect_near(v.transform_point({0, 0, 0}), {0, 0, -10});
  Mat4 p = v * v.inverse();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(p.m[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
}

// ---------------------------------------------------------------- features

TEST(SceneFeatures, NamesAndToString) {
  EXPECT_EQ(feature_name(Feature::local_lights), "local_lights");
  EXPECT_EQ(feature_name(Feature::alpha_tested), "alpha_tested");
  EXPECT_EQ(to_string(SceneFeatures{}), "none");
  EXPECT_EQ(to_string(SceneFeatures(Feature::sun) | Feature::sky), "sun,sky");
  SceneFeatures all;
  for (uint32_t i = 0; i < kFeatureCount; ++i) all |= static_cast<Feature>(1u << i);
  EXPECT_EQ(to_string(all), "sun,sky,local_lights,emissive,alpha_tested,translucent,textured,motion,decals,cloth,indoor_volumes,glossy");
}

Scene minimal_scene() {
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(make_box({1, 1, 1}));
  s.instances.push_back(Instance{});
  return s;
}

TEST(SceneFeatures, EmptySceneHasNone) { EXPECT_TRUE(minimal_scene().features().empty()); }

TEST(SceneFeatures, DecalsAndCloth) {
  Scene s = minimal_scene();
  s.decals.push_back(Decal{});
  s.decals.back().opacity = 0;
  EXPECT_FALSE(s.features().has(Feature::decals)) << "a decal of opacity 0 changes nothing";
  s.decals.push_back(Decal{});
  EXPECT_TRUE(s.features().has(Feature::decals));
  s.materials.push_back(Material{});  // unused cloth: no feature
  s.materials.back().brdf = BrdfKind::cloth;
  s.materials.back().sheen = 0.5f;
  EXPECT_FALSE(s.features().has(Feature::cloth));
  s.instances[0].material = 1;
  EXPECT_TRUE(s.features().has(Feature::cloth));
}

TEST(SceneFeatures, IndoorVolumesAreLoadedOffsetAndAFeature) {
  Scene s = minimal_scene();
  EXPECT_FALSE(s.features().has(Feature::indoor_volumes));
  s.indoor_volumes.push_back(IndoorVolume{"room", {-1, 0, -1}, {1, 2, 1}});
  EXPECT_TRUE(s.features().has(Feature::indoor_volumes));
  // flatten carries them with the world offset, as every other position.
  FlatScene f = flatten(s, 0.0f, {10000, 0, -5});
  ASSERT_EQ(f.indoor_volumes.size(), 1u);
  EXPECT_EQ(f.indoor_volumes[0].min.x, 9999.0f);
  EXPECT_EQ(f.indoor_volumes[0].max.z, -4.0f);
  Scene loaded = parse_scene(nlohmann::json::parse(R"({"materials": {"w": {}}, "objects": [{"primitive": {"type": "quad"},
      "material": "w"}], "indoor_volumes": [{"name": "hall", "min": [0, 0, 0], "max": [4, 3, 5]}]})"),
                             "mem.json");
  ASSERT_EQ(loaded.indoor_volumes.size(), 1u);
  EXPECT_EQ(loaded.indoor_volumes[0].name, "hall");
  EXPECT_EQ(loaded.indoor_volumes[0].max.z, 5.0f);
}

TEST(SceneFeatures, SunAndSky) {
  Scene s = minimal_scene();
  s.sun.enabled = true;
  EXPECT_FALSE(s.features().has(Feature::sun));  // zero irradiance lights nothing
  s.sun.irradiance = {1, 1, 1};
  EXPECT_TRUE(s.features().has(Feature::sun));
  s.sun.enabled = false;
  EXPECT_FALSE(s.features().has(Feature::sun));

  s.sky.radiance = {1, 1, 1};
  EXPECT_FALSE(s.features().has(Feature::sky));  // kind none
  s.sky.kind = SkyKind::constant;
  EXPECT_TRUE(s.features().has(Feature::sky));
  s.sky.radiance = {0, 0, 0};
  EXPECT_FALSE(s.features().has(Feature::sky));
  s.sky.kind = SkyKind::gradient;
  s.sky.horizon = {0.5f, 0, 0};
  EXPECT_TRUE(s.features().has(Feature::sky));
  EXPECT_EQ(s.features(), SceneFeatures(Feature::sky));
}

TEST(SceneFeatures, LocalLights) {
  Scene s = minimal_scene();
  s.lights.push_back(LocalLight{});
  EXPECT_EQ(s.features(), SceneFeatures(Feature::local_lights));
}

TEST(SceneFeatures, MaterialFeaturesOnlyFromUsedMaterials) {
  struct Case {
    Feature f;
    void (*set)(Material&);
  };
  Case cases[] = {
      {Feature::emissive, [](Material& m) { m.emissive = {0, 0, 2}; }},
      {Feature::alpha_tested, [](Material& m) { m.alpha = AlphaKind::checker_mask; }},
      {Feature::translucent, [](Material& m) { m.translucency = 0.25f; }},
      {Feature::textured, [](Material& m) { m.texture = TextureKind::value_noise; }},
  };
  for (const Case& c : cases) {
    Scene s = minimal_scene();
    Material unused;
    c.set(unused);
    s.materials.push_back(unused);
    EXPECT_TRUE(s.features().empty()) << feature_name(c.f);
    s.instances.push_back(Instance{});
    s.instances.back().material = 1;
    EXPECT_EQ(s.features(), SceneFeatures(c.f)) << feature_name(c.f);
  }
}

TEST(SceneFeatures, Motion) {
  Scene s = minimal_scene();
  s.instances[0].animation.push_back(Keyframe{});
  EXPECT_FALSE(s.features().has(Feature::motion));  // one key holds still
  s.instances[0].animation.push_back(Keyframe{1.0f});
  EXPECT_TRUE(s.features().has(Feature::motion));

  Scene c = minimal_scene();
  c.camera.animation = {CameraKey{0.0f}, CameraKey{1.0f}};  // two keys, same pose
  EXPECT_FALSE(c.features().has(Feature::motion));
  c.camera.animation[1].fov_y_deg = 50;
  EXPECT_TRUE(c.features().has(Feature::motion));
}

// ---------------------------------------------------------------- primitives

float triangle_area(const Mesh& m, size_t t) {
  Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
  return 0.5f * length(cross(b - a, c - a));
}

float total_area(const Mesh& m) {
  double sum = 0;
  for (size_t t = 0; t < m.indices.size() / 3; ++t) sum += triangle_area(m, t);
  return static_cast<float>(sum);
}

// Shared sanity: attribute arrays agree, indices in range, unit normals, UVs in [0,1], and
// the winding agrees with the vertex normals (counter-clockwise seen from the front).
void check_mesh(const Mesh& m, size_t expected_triangles) {
  ASSERT_EQ(m.indices.size(), 3 * expected_triangles) << m.name;
  ASSERT_EQ(m.normals.size(), m.positions.size()) << m.name;
  ASSERT_EQ(m.uvs.size(), m.positions.size()) << m.name;
  for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size()) << m.name;
  for (Vec3 n : m.normals) EXPECT_NEAR(length(n), 1.0f, 1e-5f) << m.name;
  for (Vec2 uv : m.uvs) {
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LE(uv.x, 1.0f);
    EXPECT_GE(uv.y, 0.0f);
    EXPECT_LE(uv.y, 1.0f);
  }
  for (size_t t = 0; t < expected_triangles; ++t) {
    uint32_t i0 = m.indices[3 * t], i1 = m.indices[3 * t + 1], i2 = m.indices[3 * t + 2];
    Vec3 g = cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
    EXPECT_GT(length(g), 0.0f) << m.name << " triangle " << t << " is degenerate";
    EXPECT_GT(dot(g, m.normals[i0] + m.normals[i1] + m.normals[i2]), 0.0f) << m.name << " triangle " << t;
  }
}

Vec3 bounds_extent(const Mesh& m) {
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (Vec3 p : m.positions) { lo = vmin(lo, p); hi = vmax(hi, p); }
  return hi - lo;
}

TEST(ScenePrimitives, Box) {
  Mesh m = make_box({1, 2, 3});
  check_mesh(m, 12);
  EXPECT_NEAR(total_area(m), 2 * (1 * 2 + 2 * 3 + 3 * 1), 1e-4f);
  expect_near(bounds_extent(m), {1, 2, 3});
}

TEST(ScenePrimitives, QuadEveryFacing) {
  for (Facing f : {Facing::pos_x, Facing::neg_x, Facing::pos_y, Facing::neg_y, Facing::pos_z, Facing::neg_z}) {
    Mesh m = make_quad({2, 3}, f);
    check_mesh(m, 2);
    EXPECT_NEAR(total_area(m), 6.0f, 1e-5f);
    for (Vec3 n : m.normals) expect_near(n, facing_normal(f));
    EXPECT_EQ(parse_facing(facing_name(f)), f);
  }
  expect_near(bounds_extent(make_quad({2, 3}, Facing::pos_y)), {2, 0, 3});  // floor: V along z
  EXPECT_FALSE(parse_facing("up").has_value());
}

TEST(ScenePrimitives, Sphere) {
  Mesh m = make_sphere(2.0f, 64);
  check_mesh(m, 2 * 64 * (32 - 1));
  EXPECT_NEAR(total_area(m), 4 * kPi * 4, 0.02f * 4 * kPi * 4);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(length(m.positions[i]), 2.0f, 1e-5f);
    expect_near(m.normals[i], m.positions[i] / 2.0f, 1e-5f);
  }
  check_mesh(make_sphere(1.0f, 3), 2 * 3 * (2 - 1));  // coarsest allowed
}

TEST(ScenePrimitives, Cylinder) {
  float r = 0.5f, h = 2.0f;
  Mesh capped = make_cylinder(r, h, 48, true);
  check_mesh(capped, 4 * 48);
  EXPECT_NEAR(total_area(capped), 2 * kPi * r * h + 2 * kPi * r * r, 0.01f * (2 * kPi * r * (h + r)));
  Mesh open = make_cylinder(r, h, 48, false);
  check_mesh(open, 2 * 48);
  expect_near(bounds_extent(open), {1, 2, 1}, 1e-3f);
}

TEST(ScenePrimitives, ThinSlab) {
  Mesh m = make_thin_slab({1.5f, 2.0f}, 0.02f, Facing::pos_x);
  check_mesh(m, 12);
  expect_near(bounds_extent(m), {0.02f, 2.0f, 1.5f});
  EXPECT_NEAR(total_area(m), 2 * (1.5f * 2.0f + 0.02f * 2.0f + 0.02f * 1.5f), 1e-4f);
}

// Closed primitives are wound counter-clockwise seen from outside: every face normal
// cross(b - a, c - a) points away from the (convex) primitive's centre. Solid instances
// (GpuInstance::flags) rely on it to tell the back of a face from its front.
TEST(ScenePrimitives, ClosedPrimitivesAreWoundOutwards) {
  struct Case {
    const char* name;
    Mesh mesh;
    bool closed;
  };
  std::vector<Case> cases = {{"box", make_box({1, 2, 3}), true},
                             {"thin_slab", make_thin_slab({2, 3}, 0.3f, Facing::pos_x), true},
                             {"sphere", make_sphere(1.5f, 24), true},
                             {"capped cylinder", make_cylinder(0.5f, 2.0f, 16, true), true},
                             {"open cylinder", make_cylinder(0.5f, 2.0f, 16, false), false},
                             {"quad", make_quad({1, 1}, Facing::pos_y), false},
                             {"leaf cards", make_leaf_cards(8, {1, 1, 1}, {0.1f, 0.1f}, 3), false}};
  for (const Case& c : cases) {
    EXPECT_EQ(c.mesh.closed, c.closed) << c.name;
    if (!c.closed) continue;
    size_t faces = 0, outward = 0;
    for (size_t t = 0; t + 2 < c.mesh.indices.size(); t += 3) {
      Vec3 a = c.mesh.positions[c.mesh.indices[t]], b = c.mesh.positions[c.mesh.indices[t + 1]],
           d = c.mesh.positions[c.mesh.indices[t + 2]];
      Vec3 g = cross(b - a, d - a);
      if (length(g) < 1e-9f) continue;  // the sphere's collapsed pole triangles
      ++faces;
      outward += dot(g, (a + b + d) * (1.0f / 3.0f)) > 0.0f;
    }
    EXPECT_GT(faces, 0u) << c.name;
    EXPECT_EQ(outward, faces) << c.name;
  }
}

TEST(ScenePrimitives, LeafCardsAreDeterministicAndInsideRegion) {
  Vec3 region{2, 1, 3};
  Vec2 card{0.2f, 0.1f};
  Mesh a = make_leaf_cards(100, region, card, 42);
  check_mesh(a, 200);
  EXPECT_NEAR(total_area(a), 100 * 0.2f * 0.1f, 1e-3f);
  float reach = 0.5f * length(Vec3{card.x, card.y, 0});
  for (Vec3 p : a.positions) {
    EXPECT_LE(std::fabs(p.x), 0.5f * region.x + reach);
    EXPECT_LE(std::fabs(p.y), 0.5f * region.y + reach);
    EXPECT_LE(std::fabs(p.z), 0.5f * region.z + reach);
  }
  Mesh b = make_leaf_cards(100, region, card, 42);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t i = 0; i < a.positions.size(); ++i) EXPECT_EQ(a.positions[i], b.positions[i]);
  Mesh c = make_leaf_cards(100, region, card, 43);
  EXPECT_FALSE(a.positions[0] == c.positions[0]);
}

// ---------------------------------------------------------------- animation

TEST(SceneAnimation, InstanceKeysInterpolateAndClamp) {
  Scene s = minimal_scene();
  s.instances[0].animation = {Keyframe{0.0f, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}},
                              Keyframe{2.0f, {4, 0, 0}, {0, 90, 0}, {3, 3, 3}}};
  expect_near(s.instance_transform(0, 1.0f).transform_point({0, 0, 0}), {2, 0, 0});
  // Halfway: 45 degrees about Y and scale 2.
  Vec3 p = s.instance_transform(0, 1.0f).transform_vector({1, 0, 0});
  expect_near(p, Vec3{std::sqrt(2.0f), 0, -std::sqrt(2.0f)}, 1e-5f);
  expect_near(s.instance_transform(0, -5.0f).transform_point({0, 0, 0}), {0, 0, 0});
  expect_near(s.instance_transform(0, 50.0f).transform_point({0, 0, 0}), {4, 0, 0});
  expect_near(s.instance_transform(0, std::nanf("")).transform_point({0, 0, 0}), {0, 0, 0});
  EXPECT_THROW(s.instance_transform(7, 0.0f), std::out_of_range);
}

TEST(SceneAnimation, RemovedAtCollapsesTheInstanceFromThatTimeOn) {
  Scene s = minimal_scene();
  s.instances[0].transform = Mat4::trs({1, 2, 3}, {0, 0, 0}, {2, 2, 2});
  EXPECT_FALSE(s.instances[0].changes());
  s.instances[0].removed_at = 0.5f;
  EXPECT_TRUE(s.instances[0].changes());
  EXPECT_TRUE(s.features().has(Feature::motion));
  expect_near(s.instance_transform(0, 0.49f).transform_point({1, 0, 0}), {3, 2, 3});
  // At and after the removal every vertex sits on the instance's origin: zero-area triangles.
  for (float t : {0.5f, 7.0f}) {
    const Mat4 m = s.instance_transform(0, t);
    expect_near(m.transform_point({1, 0, 0}), {1, 2, 3});
    expect_near(m.transform_point({-4, 5, 6}), {1, 2, 3});
  }
  // With keys, the collapse happens where the keys put the instance at the removal time.
  s.instances[0].animation = {Keyframe{0.0f, {0, 0, 0}}, Keyframe{1.0f, {10, 0, 0}}};
  expect_near(s.instance_transform(0, 3.0f).transform_point({1, 1, 1}), {5, 0, 0});
  FlatScene f = flatten(s, 1.0f);
  for (const GpuVertex& v : f.vertices) {
    EXPECT_TRUE(std::isfinite(v.nx) && std::isfinite(v.ny) && std::isfinite(v.nz));
    EXPECT_NEAR(v.px, 5.0f, 1e-6f);
  }
}

TEST(SceneAnimation, CameraKeys) {
  Scene s = minimal_scene();
  s.camera.animation = {CameraKey{0.0f, {0, 0, 0}, {0, 0, -1}, 40.0f}, CameraKey{1.0f, {10, 0, 0}, {10, 0, -1}, 60.0f}};
  Camera c = s.camera_at(0.25f);
  expect_near(c.position, {2.5f, 0, 0});
  expect_near(c.target, {2.5f, 0, -1});
  EXPECT_NEAR(c.fov_y_deg, 45.0f, 1e-5f);
  EXPECT_TRUE(c.animation.empty());
  expect_near(s.camera_at(9.0f).position, {10, 0, 0});
}

TEST(SceneAnimation, SunKeys) {
  Scene s = minimal_scene();
  s.sun.enabled = true;
  s.sun.direction = {0, 1, 0};
  s.sun.irradiance = {2, 2, 2};
  EXPECT_FALSE(s.lighting_changes());
  // Elevation 60 degrees -> 30 degrees in the x-y plane over one second, irradiance 2 -> 1.
  const float d60 = 60.0f * 3.14159265f / 180.0f, d30 = 30.0f * 3.14159265f / 180.0f;
  s.sun.animation = {SunKey{0.0f, {std::cos(d60), std::sin(d60), 0}, {2, 2, 2}},
                     SunKey{1.0f, {std::cos(d30), std::sin(d30), 0}, {1, 1, 1}}};
  EXPECT_TRUE(s.lighting_changes());
  EXPECT_TRUE(s.time_varying());
  EXPECT_FALSE(s.features().has(Feature::motion));  // lighting, not geometry
  // Slerp: a quarter of the way the sun is at 52.5 degrees, exactly (a lerp of the vectors would not be).
  Sun q = s.sun_at(0.25f);
  const float d525 = 52.5f * 3.14159265f / 180.0f;
  expect_near(q.direction, Vec3{std::cos(d525), std::sin(d525), 0}, 1e-5f);
  expect_near(q.irradiance, Vec3{1.75f, 1.75f, 1.75f});
  EXPECT_TRUE(q.animation.empty());
  expect_near(s.sun_at(-3.0f).direction, Vec3{std::cos(d60), std::sin(d60), 0}, 1e-6f);
  expect_near(s.sun_at(5.0f).irradiance, Vec3{1, 1, 1});
  expect_near(s.sun_at(std::nanf("")).direction, Vec3{std::cos(d60), std::sin(d60), 0}, 1e-6f);
  // Equal keys hold still; a disabled sun changes nothing.
  s.sun.animation[1] = s.sun.animation[0];
  EXPECT_FALSE(s.lighting_changes());
  s.sun.animation[1].irradiance = {0, 0, 0};
  EXPECT_TRUE(s.lighting_changes());
  s.sun.enabled = false;
  EXPECT_FALSE(s.lighting_changes());
}

TEST(SceneAnimation, SunKeysLoaded) {
  Scene s = parse_scene(nlohmann::json::parse(R"({"materials": {"m": {}}, "objects": [{"primitive": {"type": "box"}, "material": "m"}],
    "sun": {"direction": [0, 1, 0], "irradiance": [1, 1, 1],
            "animation": [{"time": 0}, {"time": 2, "direction": [1, 1, 0]}, {"time": 3, "irradiance": [0, 0, 0]}]}})"),
                              "sun.json");
  ASSERT_EQ(s.sun.animation.size(), 3u);
  expect_near(s.sun.animation[0].direction, {0, 1, 0});  // missing fields take the static values
  expect_near(s.sun.animation[1].direction, Vec3{std::sqrt(0.5f), std::sqrt(0.5f), 0}, 1e-6f);  // normalised
  expect_near(s.sun.animation[1].irradiance, {1, 1, 1});
  expect_near(s.sun.animation[2].irradiance, {0, 0, 0});
  expect_near(s.sun.animation[2].direction, {0, 1, 0});
  EXPECT_TRUE(s.lighting_changes());
  EXPECT_TRUE(s.features().has(Feature::sun));
}

// ---------------------------------------------------------------- flatten

TEST(SceneFlatten, TransformsPositionsAndNormals) {
  Scene s = minimal_scene();
  s.instances[0].transform = Mat4::trs({10, 0, 0}, {0, 0, 30}, {4, 1, 1});
  s.instances.push_back(Instance{});  // second copy, untransformed
  FlatScene f = flatten(s, 0.0f);
  ASSERT_EQ(f.vertices.size(), 48u);
  ASSERT_EQ(f.triangles.size(), 24u);
  ASSERT_EQ(f.instances.size(), 2u);
  EXPECT_EQ(f.instances[1].first_triangle, 12u);
  EXPECT_EQ(f.instances[1].triangle_count, 12u);
  EXPECT_EQ(f.triangles[12].instance, 1u);
  EXPECT_EQ(f.triangles[12].i0, 24u + s.meshes[0].indices[0]);
  for (size_t i = 0; i < 24; ++i) {
    Vec3 expected = s.instances[0].transform.transform_point(s.meshes[0].positions[i]);
    expect_near({f.vertices[i].px, f.vertices[i].py, f.vertices[i].pz}, expected, 1e-5f);
  }
  // Under non-uniform scale the normal must stay perpendicular to the transformed faces.
  for (const GpuTriangle& t : f.triangles) {
    auto pos = [&](uint32_t i) { return Vec3{f.vertices[i].px, f.vertices[i].py, f.vertices[i].pz}; };
    Vec3 n{f.vertices[t.i0].nx, f.vertices[t.i0].ny, f.vertices[t.i0].nz};
    EXPECT_NEAR(length(n), 1.0f, 1e-5f);
    Vec3 g = normalize(cross(pos(t.i1) - pos(t.i0), pos(t.i2) - pos(t.i0)));
    EXPECT_NEAR(dot(g, n), 1.0f, 1e-4f);
  }
}

TEST(SceneFlatten, MirroredInstanceNormalsPointOutward) {
  Scene s = minimal_scene();
  s.instances[0].transform = Mat4::trs({0, 0, 0}, {0, 0, 0}, {-2, 1, 1});
  FlatScene f = flatten(s, 0.0f);
  for (const GpuVertex& v : f.vertices) EXPECT_GT(v.px * v.nx + v.py * v.ny + v.pz * v.nz, 0.0f);
}

TEST(SceneFlatten, DegenerateInputStaysFinite) {
  Scene s = minimal_scene();
  Mesh bad;
  bad.name = "degenerate";
  bad.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  bad.normals = {{0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};  // a zero normal must stay zero
  bad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  bad.indices = {0, 1, 2, 0, 0, 0, 0, 1, 3};  // collinear, collapsed, then a real triangle
  s.meshes.push_back(bad);
  s.instances[0].mesh = 1;
  s.instances[0].transform = Mat4::trs({1, 2, 3}, {10, 20, 30}, {1, 2, 3});
  Instance flat;
  flat.mesh = 0;
  flat.transform = Mat4::scaling({1, 0, 1});  // collapsed to a plane
  s.instances.push_back(flat);
  FlatScene f = flatten(s, 0.0f);
  EXPECT_EQ(f.instances[0].triangle_count, 3u);  // zero-area triangles survive
  EXPECT_EQ(f.triangles.size(), 3u + 12u);
  for (const GpuVertex& v : f.vertices) {
    EXPECT_TRUE(finite({v.px, v.py, v.pz}));
    Vec3 n{v.nx, v.ny, v.nz};
    ASSERT_TRUE(finite(n));
    float len = length(n);
    EXPECT_TRUE(len == 0.0f || std::fabs(len - 1.0f) < 1e-5f) << len;
  }
  EXPECT_EQ(f.vertices[0].nx, 0.0f);
  EXPECT_EQ(f.vertices[0].ny, 0.0f);
  EXPECT_EQ(f.vertices[0].nz, 0.0f);
}

TEST(SceneFlatten, MaterialsAndLights) {
  Scene s = minimal_scene();
  s.materials[0].albedo = {0.1f, 0.2f, 0.3f};
  s.materials[0].alpha = AlphaKind::opacity;
  s.materials[0].opacity = 0.4f;
  LocalLight l;
  l.kind = LightKind::spot;
  l.direction = {0, -2, 0};
  l.inner_cone_deg = 60;
  l.outer_cone_deg = 90;
  s.lights.push_back(l);
  FlatScene f = flatten(s, 0.0f);
  ASSERT_EQ(f.materials.size(), 1u);
  EXPECT_EQ(f.materials[0].albedo[2], 0.3f);
  EXPECT_EQ(f.materials[0].alpha, static_cast<uint32_t>(AlphaKind::opacity));
  EXPECT_EQ(f.materials[0].opacity, 0.4f);
  ASSERT_EQ(f.lights.size(), 1u);
  EXPECT_EQ(f.lights[0].kind, 1u);
  EXPECT_NEAR(f.lights[0].cos_inner, 0.5f, 1e-6f);
  EXPECT_NEAR(f.lights[0].cos_outer, 0.0f, 1e-6f);
  EXPECT_NEAR(f.lights[0].direction[1], -1.0f, 1e-6f);
  static_assert(sizeof(GpuVertex) == 32 && sizeof(GpuMaterial) == 112 && sizeof(GpuLight) == 64);
}

TEST(SceneFlatten, AnimatedInstanceUsesTime) {
  Scene s = minimal_scene();
  s.instances[0].animation = {Keyframe{0.0f, {0, 0, 0}}, Keyframe{1.0f, {0, 10, 0}}};
  FlatScene a = flatten(s, 0.0f), b = flatten(s, 0.5f);
  EXPECT_NEAR(b.vertices[0].py - a.vertices[0].py, 5.0f, 1e-5f);
}

// ---------------------------------------------------------------- loader

json minimal_doc() {
  return json::parse(R"({
    "materials": {"white": {}},
    "objects": [{"primitive": {"type": "box"}, "material": "white"}]
  })");
}

std::string error_of(const json& doc) {
  try {
    parse_scene(doc, "bad_scene.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

// "solid": thin_slab is solid unless it says otherwise, other closed primitives only when they
// say so; flatten carries it into GpuInstance::flags, with the mirrored bit for a negative
// determinant; an open primitive cannot be solid.
TEST(SceneLoader, SolidObjectsAndTheirInstanceFlags) {
  json doc = json::parse(R"({
    "materials": {"white": {}},
    "objects": [
      {"primitive": {"type": "thin_slab", "size": [2, 2], "thickness": 0.3}, "material": "white"},
      {"primitive": {"type": "thin_slab", "size": [2, 2], "thickness": 0.3}, "material": "white", "solid": false},
      {"primitive": {"type": "box"}, "material": "white"},
      {"primitive": {"type": "box"}, "material": "white", "solid": true, "transform": {"scale": [-1, 1, 1]}},
      {"primitive": {"type": "sphere"}, "material": "white", "solid": true},
      {"primitive": {"type": "quad"}, "material": "white"}
    ]
  })");
  Scene s = parse_scene(doc, "solid.json");
  FlatScene f = flatten(s, 0.0f);
  ASSERT_EQ(f.instances.size(), 6u);
  const uint32_t expect[6] = {kInstanceSolid, 0u, 0u, kInstanceSolid | kInstanceMirrored, kInstanceSolid, 0u};
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(f.instances[i].flags, expect[i]) << "object " << i << " (no normal map: no kInstanceNormalMapped)";

  json bad = minimal_doc();
  bad["objects"][0] = {{"primitive", {{"type", "quad"}}}, {"material", "white"}, {"solid", true}};
  EXPECT_NE(error_of(bad).find("solid"), std::string::npos) << error_of(bad);
  bad["objects"][0] = {{"primitive", {{"type", "cylinder"}, {"capped", false}}}, {"material", "white"}, {"solid", true}};
  EXPECT_NE(error_of(bad).find("closed primitive"), std::string::npos) << error_of(bad);
  bad["objects"][0] = {{"primitive", {{"type", "box"}}}, {"material", "white"}, {"solid", 1}};
  EXPECT_NE(error_of(bad).find("solid"), std::string::npos) << error_of(bad);
}

TEST(SceneLoader, MinimalSceneUsesDefaults) {
  Scene s = parse_scene(minimal_doc(), "mini.json");
  EXPECT_EQ(s.source, "mini.json");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "white");
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].name, "object0");
  EXPECT_EQ(s.meshes[0].indices.size(), 36u);
  EXPECT_FALSE(s.sun.enabled);
  EXPECT_EQ(s.sky.kind, SkyKind::none);
  EXPECT_NEAR(s.frame_time, 1.0f / 60.0f, 1e-7f);
  EXPECT_TRUE(s.features().empty());
}

TEST(SceneLoader, IdenticalPrimitivesShareOneMesh) {
  json doc = minimal_doc();
  doc["objects"].push_back(json::parse(R"({"primitive": {"type": "box", "size": [1, 1, 1]}, "material": "white",
                                           "transform": {"translate": [3, 0, 0]}})"));
  doc["objects"].push_back(json::parse(R"({"primitive": {"type": "box", "size": [2, 1, 1]}, "material": "white"})"));
  Scene s = parse_scene(doc, "share.json");
  ASSERT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.instances[0].mesh, s.instances[1].mesh);
  EXPECT_NE(s.instances[0].mesh, s.instances[2].mesh);
}

TEST(SceneLoader, AnimationChannelsDefaultToStaticTransform) {
  json doc = minimal_doc();
  doc["objects"][0]["transform"] = {{"translate", {1, 2, 3}}, {"scale", {2, 2, 2}}};
  doc["objects"][0]["animation"] = json::parse(R"([{"time": 0}, {"time": 1, "translate": [5, 2, 3]}])");
  Scene s = parse_scene(doc, "anim.json");
  ASSERT_EQ(s.instances[0].animation.size(), 2u);
  expect_near(s.instances[0].animation[0].translation, {1, 2, 3});
  expect_near(s.instances[0].animation[1].scale, {2, 2, 2});
  EXPECT_TRUE(s.features().has(Feature::motion));
}

TEST(SceneLoader, RemovedAt) {
  json doc = minimal_doc();
  Scene kept = parse_scene(doc, "kept.json");
  EXPECT_FALSE(kept.instances[0].removable());
  EXPECT_FALSE(kept.features().has(Feature::motion));
  doc["objects"][0]["removed_at"] = 0.25;
  Scene s = parse_scene(doc, "removed.json");
  EXPECT_FLOAT_EQ(s.instances[0].removed_at, 0.25f);
  EXPECT_TRUE(s.features().has(Feature::motion));
}

// A valid one-triangle mesh primitive for object 0; returns it for edits.
json& set_mesh(json& d) {
  d["objects"][0]["primitive"] =
      json::parse(R"({"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]]})");
  return d["objects"][0]["primitive"];
}

struct BadCase {
  const char* what;
  void (*edit)(json&);
  const char* pointer;   // exact JSON pointer expected in the message
  const char* fragment;  // and a piece of the expected/got text
};

const BadCase kBadCases[] = {
    {"sheen on a standard material", [](json& d) { d["materials"]["white"]["sheen"] = 0.5; },
     "/materials/white/sheen", "no sheen for brdf \"standard\""},
    {"cloth without sheen", [](json& d) { d["materials"]["white"]["brdf"] = "cloth"; }, "/materials/white/sheen",
     "got missing key"},
    {"cloth with zero sheen", [](json& d) { d["materials"]["white"].update({{"brdf", "cloth"}, {"sheen", 0}}); },
     "/materials/white/sheen", "expected number in (0, 1], got 0"},
    {"translucent cloth", [](json& d) {
       d["materials"]["white"].update({{"brdf", "cloth"}, {"sheen", 0.3}, {"translucency", 0.2}});
     }, "/materials/white/translucency", "0 for brdf \"cloth\""},
    {"unknown brdf", [](json& d) { d["materials"]["white"]["brdf"] = "skin"; }, "/materials/white/brdf",
     "one of \"standard\", \"cloth\", \"glossy\", got \"skin\""},
    {"decals not an array", [](json& d) { d["decals"] = 3; }, "/decals", "expected array, got 3"},
    {"decal without position", [](json& d) { d["decals"] = json::parse(R"([{"size": [1, 1, 1], "albedo": [0, 0, 0]}])"); },
     "/decals/0/position", "got missing key"},
    {"decal of zero size", [](json& d) {
       d["decals"] = json::parse(R"([{"position": [0, 0, 0], "size": [1, 0, 1], "albedo": [0, 0, 0]}])");
     }, "/decals/0/size/1", "expected number > 0, got 0"},
    {"decal albedo above 1", [](json& d) {
       d["decals"] = json::parse(R"([{"position": [0, 0, 0], "size": [1, 1, 1], "albedo": [0, 2, 0]}])");
     }, "/decals/0/albedo/1", "expected number in [0, 1], got 2"},
    {"decal opacity above 1", [](json& d) {
       d["decals"] = json::parse(R"([{"position": [0, 0, 0], "size": [1, 1, 1], "albedo": [0, 0, 0], "opacity": 1.5}])");
     }, "/decals/0/opacity", "got 1.5"},
    {"unknown decal shape", [](json& d) {
       d["decals"] = json::parse(R"([{"position": [0, 0, 0], "size": [1, 1, 1], "albedo": [0, 0, 0], "shape": "star"}])");
     }, "/decals/0/shape", "one of \"rect\", \"disc\", got \"star\""},
    {"unknown decal key", [](json& d) {
       d["decals"] = json::parse(R"([{"position": [0, 0, 0], "size": [1, 1, 1], "albedo": [0, 0, 0], "normal": 1}])");
     }, "/decals/0/normal", "unknown key \"normal\""},
    {"too many decals", [](json& d) {
       d["decals"] = json::array();
       for (int i = 0; i < 17; ++i) d["decals"].push_back(json::parse(R"({"position": [0, 0, 0], "size": [1, 1, 1], "albedo": [0, 0, 0]})"));
     }, "/decals", "expected at most 16 decals (the frame constants hold 16), got 17 decals"},
    {"indoor volume max not above min", [](json& d) {
       d["indoor_volumes"] = json::parse(R"([{"min": [0, 0, 0], "max": [1, 0, 1]}])");
     }, "/indoor_volumes/0/max", "expected a corner above \"min\" on every axis, got [1, 0, 1] with min [0, 0, 0]"},
    {"indoor volume without min", [](json& d) { d["indoor_volumes"] = json::parse(R"([{"max": [1, 1, 1]}])"); },
     "/indoor_volumes/0/min", "got missing key"},
    {"indoor volume unknown key", [](json& d) {
       d["indoor_volumes"] = json::parse(R"([{"min": [0, 0, 0], "max": [1, 1, 1], "planes": 2}])");
     }, "/indoor_volumes/0/planes", "unknown key \"planes\""},
    {"too many indoor volumes", [](json& d) {
       d["indoor_volumes"] = json::array();
       for (int i = 0; i < 9; ++i) d["indoor_volumes"].push_back(json::parse(R"({"min": [0, 0, 0], "max": [1, 1, 1]})"));
     }, "/indoor_volumes", "expected at most 8 indoor volumes (the frame constants hold 8), got 9 volumes"},
    {"root is not an object", [](json& d) { d = json::array({1, 2}); }, "/", "expected object, got array of 2 elements"},
    {"objects missing", [](json& d) { d.erase("objects"); }, "/objects", "got missing key"},
    {"objects empty", [](json& d) { d["objects"] = json::array(); }, "/objects", "got empty array"},
    {"object is a number", [](json& d) { d["objects"][0] = 5; }, "/objects/0", "expected object, got 5"},
    {"materials empty", [](json& d) { d["materials"] = json::object(); }, "/materials", "got empty object"},
    {"unknown material", [](json& d) { d["objects"][0]["material"] = "whte"; }, "/objects/0/material",
     "expected the name of a material (white), got \"whte\""},
    {"material not a string", [](json& d) { d["objects"][0]["material"] = 3; }, "/objects/0/material",
     "expected string, got 3"},
    {"unknown primitive", [](json& d) { d["objects"][0]["primitive"]["type"] = "torus"; }, "/objects/0/primitive/type",
     "got \"torus\""},
    {"primitive type missing", [](json& d) { d["objects"][0]["primitive"].erase("type"); },
     "/objects/0/primitive/type", "got missing key"},
    {"negative size", [](json& d) { d["objects"][0]["primitive"]["size"] = {1, -1, 1}; },
     "/objects/0/primitive/size/1", "expected number > 0, got -1"},
    {"size of wrong length", [](json& d) { d["objects"][0]["primitive"]["size"] = {1, 1}; },
     "/objects/0/primitive/size", "expected array of 3 numbers, got array of 2 elements"},
    {"key of another primitive", [](json& d) { d["objects"][0]["primitive"]["radius"] = 1; },
     "/objects/0/primitive/radius", "expected one of the keys type, size, got unknown key \"radius\""},
    {"fractional segments", [](json& d) { d["objects"][0]["primitive"] = {{"type", "sphere"}, {"segments", 2.5}}; },
     "/objects/0/primitive/segments", "expected integer in [3, 4096], got 2.5"},
    {"NaN albedo", [](json& d) { d["materials"]["white"]["albedo"] = {std::nan(""), 0, 0}; },
     "/materials/white/albedo/0", "got NaN"},
    {"albedo above one", [](json& d) { d["materials"]["white"]["albedo"] = {0.5, 1.5, 0.5}; },
     "/materials/white/albedo/1", "expected number in [0, 1], got 1.5"},
    {"roughness is a string", [](json& d) { d["materials"]["white"]["roughness"] = "high"; },
     "/materials/white/roughness", "expected number in [0, 1], got \"high\""},
    {"typo in material key", [](json& d) { d["materials"]["white"]["albdo"] = {1, 1, 1}; },
     "/materials/white/albdo", "expected one of the keys albedo, roughness"},
    {"escaped material name", [](json& d) { d["materials"]["a/b~c"] = {{"x", 1}}; }, "/materials/a~1b~0c/x",
     "unknown key \"x\""},
    {"unknown alpha mode", [](json& d) { d["materials"]["white"]["alpha"] = "leafmask"; }, "/materials/white/alpha",
     "expected one of \"none\", \"leaf_mask\", \"checker_mask\", \"opacity\", got \"leafmask\""},
    {"float overflow", [](json& d) { d["objects"][0]["transform"] = {{"translate", {1e39, 0, 0}}}; },
     "/objects/0/transform/translate/0", "expected finite number"},
    {"empty animation", [](json& d) { d["objects"][0]["animation"] = json::array(); }, "/objects/0/animation",
     "expected non-empty array, got empty array"},
    {"removed_at negative", [](json& d) { d["objects"][0]["removed_at"] = -1; }, "/objects/0/removed_at",
     "expected number >= 0, got -1"},
    {"removed_at not a number", [](json& d) { d["objects"][0]["removed_at"] = "soon"; }, "/objects/0/removed_at",
     "got \"soon\""},
    {"keys out of order",
     [](json& d) { d["objects"][0]["animation"] = json::parse(R"([{"time": 1}, {"time": 0.5}])"); },
     "/objects/0/animation/1/time", "expected time > 1 (the previous key's), got 0.5"},
    {"point light without intensity", [](json& d) { d["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0]}])"); },
     "/lights/0/intensity", "expected array of 3 numbers, got missing key"},
    {"point light with a direction",
     [](json& d) {
       d["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1], "direction": [0, -1, 0]}])");
     },
     "/lights/0/direction", "expected one of the keys type, position, intensity, range"},
    {"spot cone inverted",
     [](json& d) {
       d["lights"] = json::parse(R"([{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
                                      "intensity": [1, 1, 1], "inner_cone_deg": 40, "outer_cone_deg": 30}])");
     },
     "/lights/0/inner_cone_deg", "expected number <= outer_cone_deg (30), got 40"},
    {"lights not an array", [](json& d) { d["lights"] = json::object(); }, "/lights", "expected array, got empty object"},
    {"sun direction zero", [](json& d) { d["sun"] = json::parse(R"({"direction": [0, 0, 0], "irradiance": [1, 1, 1]})"); },
     "/sun/direction", "expected non-zero direction vector, got [0, 0, 0]"},
    {"sun keys out of order",
     [](json& d) {
       d["sun"] = json::parse(R"({"direction": [0, 1, 0], "irradiance": [1, 1, 1], "animation": [{"time": 1}, {"time": 1}]})");
     },
     "/sun/animation/1/time", "expected time > 1 (the previous key's), got 1"},
    {"sun key opposite the previous",
     [](json& d) {
       d["sun"] = json::parse(
           R"({"direction": [0, 1, 0], "irradiance": [1, 1, 1], "animation": [{"time": 0}, {"time": 1, "direction": [0, -1, 0]}]})");
     },
     "/sun/animation/1/direction", "expected a direction less than 177 degrees from the previous key's"},
    {"sun key typo",
     [](json& d) {
       d["sun"] = json::parse(R"({"direction": [0, 1, 0], "irradiance": [1, 1, 1], "animation": [{"time": 0, "irradiaance": 1}]})");
     },
     "/sun/animation/0/irradiaance", "expected one of the keys time, direction, irradiance"},
    {"gradient sky without horizon", [](json& d) { d["sky"] = json::parse(R"({"type": "gradient", "radiance": [1, 1, 1]})"); },
     "/sky/horizon", "got missing key"},
    {"camera far before near", [](json& d) { d["camera"] = json::parse(R"({"near": 1, "far": 0.5})"); }, "/camera/far",
     "expected number > 1, got 0.5"},
    {"camera target at eye", [](json& d) { d["camera"] = json::parse(R"({"position": [1, 2, 3], "target": [1, 2, 3]})"); },
     "/camera/target", "expected target different from position"},
    {"frame time zero", [](json& d) { d["frame_time"] = 0; }, "/frame_time", "expected number > 0, got 0"},
    {"unknown top-level key", [](json& d) { d["lihgts"] = json::array(); }, "/lihgts",
     "expected one of the keys materials, objects, lights, decals, indoor_volumes, sun, sky, camera, frame_time"},
    // mesh primitive (kMeshDoc: 3 positions, 1 triangle)
    {"mesh index out of range", [](json& d) { set_mesh(d)["indices"] = json::parse("[[0, 1, 2], [0, 2, 3]]"); },
     "/objects/0/primitive/indices/1/2", "expected integer in [0, 2], got 3"},
    {"mesh negative index", [](json& d) { set_mesh(d)["indices"][0][1] = -1; }, "/objects/0/primitive/indices/0/1",
     "expected integer in [0, 2], got -1"},
    {"mesh fractional index", [](json& d) { set_mesh(d)["indices"][0][0] = 0.5; }, "/objects/0/primitive/indices/0/0",
     "expected integer in [0, 2], got 0.5"},
    {"mesh triangle of two indices", [](json& d) { set_mesh(d)["indices"][0] = {0, 1}; },
     "/objects/0/primitive/indices/0", "expected array of 3 vertex indices, got array of 2 elements"},
    {"mesh flat index list", [](json& d) { set_mesh(d)["indices"] = {0, 1, 2}; }, "/objects/0/primitive/indices/0",
     "expected array of 3 vertex indices, got 0"},
    {"mesh without indices", [](json& d) { set_mesh(d).erase("indices"); }, "/objects/0/primitive/indices",
     "expected non-empty array, got missing key"},
    {"mesh without positions", [](json& d) { set_mesh(d)["positions"] = json::array(); },
     "/objects/0/primitive/positions", "expected non-empty array, got empty array"},
    {"mesh position of two numbers", [](json& d) { set_mesh(d)["positions"][1] = {1, 0}; },
     "/objects/0/primitive/positions/1", "expected array of 3 numbers, got array of 2 elements"},
    {"mesh NaN position", [](json& d) { set_mesh(d)["positions"][2][1] = std::nan(""); },
     "/objects/0/primitive/positions/2/1", "expected finite number, got NaN"},
    {"mesh position overflowing float", [](json& d) { set_mesh(d)["positions"][0][0] = 1e39; },
     "/objects/0/primitive/positions/0/0", "expected finite number"},
    {"mesh null position", [](json& d) { set_mesh(d)["positions"][0] = nullptr; }, "/objects/0/primitive/positions/0",
     "expected array of 3 numbers, got null"},
    {"mesh normals not one per position", [](json& d) { set_mesh(d)["normals"] = json::parse("[[0, 1, 0], null]"); },
     "/objects/0/primitive/normals", "expected array of 3 normals (one per position), got array of 2 elements"},
    {"mesh normal is a string", [](json& d) { set_mesh(d)["normals"] = json::parse(R"([[0, 1, 0], "up", null])"); },
     "/objects/0/primitive/normals/1", "expected array of 3 numbers or null, got \"up\""},
    {"mesh infinite normal component",
     [](json& d) { set_mesh(d)["normals"] = {{0, 1, 0}, {0, HUGE_VAL, 0}, nullptr}; },
     "/objects/0/primitive/normals/1/1", "expected finite number, got inf"},
    {"mesh uvs not one per position", [](json& d) { set_mesh(d)["uvs"] = json::parse("[[0, 0]]"); },
     "/objects/0/primitive/uvs", "expected array of 3 uvs (one per position), got array of 1 element"},
    {"mesh uv of three numbers", [](json& d) { set_mesh(d)["uvs"] = json::parse("[[0, 0], [1, 0, 0], [0, 1]]"); },
     "/objects/0/primitive/uvs/1", "expected array of 2 numbers, got array of 3 elements"},
    {"mesh unknown key", [](json& d) { set_mesh(d)["colors"] = json::array(); }, "/objects/0/primitive/colors",
     "expected one of the keys type, positions, indices, normals, uvs, got unknown key \"colors\""},
};

// The mesh primitive keeps degenerate input as written: zero-area triangles, duplicate vertices,
// zero and null (NaN) normals; flatten passes a NaN normal on for the GPU guard to repair.
TEST(SceneLoader, MeshPrimitiveKeepsDegenerateInput) {
  json doc = minimal_doc();
  doc["objects"][0]["primitive"] = json::parse(R"({
    "type": "mesh",
    "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0], [2, 0, 0]],
    "indices": [[0, 1, 2], [0, 0, 1], [0, 1, 4], [1, 3, 1]],
    "normals": [[0, 0, 2], null, [0, 0, 0], [0, 0, 1], [0, 0, 1]],
    "uvs": [[0, 0], [1, 0], [0, 1], [1, 0], [2, 0]]
  })");
  json plain = json::parse(R"({"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]]})");
  doc["objects"].push_back({{"primitive", doc["objects"][0]["primitive"]}, {"material", "white"}});
  doc["objects"].push_back({{"primitive", plain}, {"material", "white"}, {"transform", {{"translate", {0, 0, 5}}}}});
  Scene s = parse_scene(doc, "mesh.json");
  ASSERT_EQ(s.meshes.size(), 2u);  // identical descriptions share one mesh
  EXPECT_EQ(s.instances[0].mesh, s.instances[1].mesh);
  const Mesh& m = s.meshes[s.instances[0].mesh];
  EXPECT_EQ(m.name, "mesh positions=5 triangles=4");
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.positions[4], (Vec3{2, 0, 0}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 0, 1, 0, 1, 4, 1, 3, 1}));
  ASSERT_EQ(m.normals.size(), 5u);
  EXPECT_EQ(m.normals[0], (Vec3{0, 0, 2}));  // kept as written; flatten normalises
  EXPECT_TRUE(std::isnan(m.normals[1].x) && std::isnan(m.normals[1].y) && std::isnan(m.normals[1].z));
  EXPECT_EQ(m.normals[2], (Vec3{0, 0, 0}));
  ASSERT_EQ(m.uvs.size(), 5u);
  EXPECT_EQ(m.uvs[4].x, 2.0f);
  const Mesh& p = s.meshes[s.instances[2].mesh];
  EXPECT_TRUE(p.normals.empty());  // no normals: zero normals after flatten, shading uses the face normal
  EXPECT_TRUE(p.uvs.empty());

  FlatScene f = flatten(s, 0.0f);
  EXPECT_EQ(f.instances[0].triangle_count, 4u);  // degenerate triangles are kept (the BVH skips them)
  ASSERT_EQ(f.vertices.size(), 13u);
  EXPECT_NEAR(f.vertices[0].nz, 1.0f, 1e-6f);
  EXPECT_TRUE(std::isnan(f.vertices[1].nx) && std::isnan(f.vertices[1].ny) && std::isnan(f.vertices[1].nz));
  EXPECT_EQ(f.vertices[2].nx, 0.0f);
  EXPECT_EQ(f.vertices[2].ny, 0.0f);
  EXPECT_EQ(f.vertices[2].nz, 0.0f);
  for (uint32_t v = 10; v < 13; ++v) {
    EXPECT_EQ(length({f.vertices[v].nx, f.vertices[v].ny, f.vertices[v].nz}), 0.0f);
    EXPECT_NEAR(f.vertices[v].pz, 5.0f, 1e-6f);
  }
}

TEST(SceneLoader, MalformedInputsNameFileAndPointer) {
  for (const BadCase& c : kBadCases) {
    json doc = minimal_doc();
    c.edit(doc);
    std::string msg = error_of(doc);
    std::string prefix = "bad_scene.json: " + std::string(c.pointer) + ": expected ";
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << c.what << "\n  message: " << msg << "\n  wanted prefix: " << prefix;
    EXPECT_NE(msg.find(c.fragment), std::string::npos) << c.what << "\n  message: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << c.what;
    if (std::getenv("GIB_PRINT_SCENE_ERRORS")) std::printf("%s\n", msg.c_str());
  }
}

// Replaces every value below `root` of `original` (and `root` itself, and every ancestor up to
// it) by each of `replacements`, and removes every key; `load` parses a document and must either
// accept it or throw a well-formed SceneError whose message starts with `prefix`. Returns
// {accepted, rejected}.
std::pair<size_t, size_t> mutate_scene(const json& original, const json::json_pointer& root,
                                       const std::vector<json>& replacements, const std::string& prefix,
                                       const std::function<void(const json&)>& load) {
  json flat = original[root].flatten();
  std::set<std::string> seen;
  std::vector<json::json_pointer> pointers;
  for (auto it = flat.begin(); it != flat.end(); ++it)  // every ancestor too: whole objects and arrays
    for (json::json_pointer p(it.key()); !p.empty(); p = p.parent_pointer())
      if (seen.insert(p.to_string()).second) pointers.push_back(root / p);
  size_t accepted = 0, rejected = 0;
  auto check = [&](const json& doc, const std::string& what) {
    try {
      load(doc);
      ++accepted;
    } catch (const SceneError& e) {
      ++rejected;
      std::string msg = e.what();
      EXPECT_EQ(msg.rfind(prefix, 0), 0u) << what << ": " << msg;
      EXPECT_NE(msg.find(": expected "), std::string::npos) << what << ": " << msg;
      EXPECT_NE(msg.find(", got "), std::string::npos) << what << ": " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << what << ": escaped as " << e.what();
    }
  };
  for (const json::json_pointer& p : pointers) {
    for (const json& r : replacements) {
      json doc = original;
      doc[p] = r;
      check(doc, p.to_string() + " = " + r.dump());
    }
    json doc = original;
    json& parent = doc[p.parent_pointer()];
    if (parent.is_object())
      parent.erase(p.back());
    else
      parent.erase(static_cast<size_t>(std::stoul(p.back())));
    check(doc, "remove " + p.to_string());
  }
  return {accepted, rejected};
}

// Every value of a full scene replaced by every kind of wrong value, and every key removed:
// the loader either accepts the document or throws a well-formed SceneError, nothing else.
TEST(SceneLoader, MutatedScenesNeverEscapeAsOtherErrors) {
  std::ifstream in(scene_path("features_zoo.json"));
  json original = json::parse(in);
  // Coarse meshes keep the thousands of parses below fast; the structure is what matters.
  for (json& object : original["objects"]) {
    json& prim = object["primitive"];
    if (prim.contains("segments")) prim["segments"] = 3;
    if (prim.contains("count")) prim["count"] = 2;
  }
  auto [accepted, rejected] = mutate_scene(
      original, json::json_pointer(""),
      {nullptr, true, -1, 0, 2.5, 1e39, std::nan(""), "x", json::array(), json::object(), json::array({1, 2, 3}),
       json::array({"a", "b", "c"})},
      "zoo: /", [](const json& doc) { parse_scene(doc, "zoo"); });
  EXPECT_GT(accepted, 0u);
  EXPECT_GT(rejected, 1000u);
}

// The same for a mesh primitive: every value and every key of it replaced or removed.
TEST(SceneLoader, MutatedMeshesNeverEscapeAsOtherErrors) {
  json original = minimal_doc();
  original["objects"][0]["primitive"] = json::parse(R"({"type": "mesh",
    "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2], [0, 0, 1]],
    "normals": [[0, 0, 1], null, [0, 0, 0]], "uvs": [[0, 0], [1, 0], [0, 1]]})");
  auto [accepted, rejected] = mutate_scene(
      original, json::json_pointer("/objects/0/primitive"),
      {nullptr, true, -1, 0, 3, 2.5, 1e39, std::nan(""), "x", json::array(), json::object(), json::array({1, 2, 3}),
       json::array({json::array({0, 1, 2})})},
      "mesh: /objects/0/primitive",
      // accepted meshes must also flatten (indices in range)
      [](const json& doc) { flatten(parse_scene(doc, "mesh"), 0.0f); });
  EXPECT_GT(accepted, 0u);
  EXPECT_GT(rejected, 100u);
}

class TempFile {
 public:
  TempFile(const std::string& name, const std::string& text)
      : path_(std::filesystem::temp_directory_path() / ("gib_test_scene_" + name)) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

std::string load_error(const std::string& path) {
  try {
    load_scene(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(SceneLoader, FileErrors) {
  std::string missing = load_error("/nonexistent/dir/gone.json");
  EXPECT_EQ(missing.rfind("/nonexistent/dir/gone.json: expected a readable file, got ", 0), 0u) << missing;

  std::string dir = load_error(std::filesystem::temp_directory_path().string());
  EXPECT_NE(dir.find("expected a scene file, got a directory"), std::string::npos) << dir;

  TempFile broken("broken.json", "{\n  \"materials\": {\"white\": {}},\n  \"objects\": [,]\n}\n");
  std::string syntax = load_error(broken.path());
  EXPECT_EQ(syntax.rfind(broken.path() + ": line 3, column 15: expected valid JSON, got ", 0), 0u) << syntax;
  EXPECT_EQ(syntax.find('\n'), std::string::npos);

  TempFile overflow("overflow.json", R"({"frame_time": 1e999})");
  std::string big = load_error(overflow.path());
  EXPECT_EQ(big.rfind(overflow.path() + ": expected valid JSON, got ", 0), 0u) << big;

  TempFile bad_utf8("utf8.json", "{\"materials\": {\"w\xff\": {}}}");
  std::string utf8 = load_error(bad_utf8.path());
  EXPECT_NE(utf8.find("expected valid JSON"), std::string::npos) << utf8;
  for (char ch : utf8) EXPECT_LT(static_cast<unsigned char>(ch), 0x80) << utf8;

  TempFile empty("empty.json", "");
  EXPECT_NE(load_error(empty.path()).find("expected valid JSON"), std::string::npos);

  TempFile wrong("wrong.json", R"({"materials": {"white": {}}, "objects": [{"primitive": {"type": "box"}, "material": "red"}]})");
  std::string ref = load_error(wrong.path());
  EXPECT_EQ(ref.rfind(wrong.path() + ": /objects/0/material: expected", 0), 0u) << ref;
}

// ---------------------------------------------------------------- sample scenes

Vec3 world_extent_lo(const FlatScene& f, uint32_t instance, bool hi) {
  Vec3 lo{1e30f, 1e30f, 1e30f}, up{-1e30f, -1e30f, -1e30f};
  const GpuInstance& in = f.instances[instance];
  for (uint32_t t = in.first_triangle; t < in.first_triangle + in.triangle_count; ++t)
    for (uint32_t i : {f.triangles[t].i0, f.triangles[t].i1, f.triangles[t].i2}) {
      Vec3 p{f.vertices[i].px, f.vertices[i].py, f.vertices[i].pz};
      lo = vmin(lo, p);
      up = vmax(up, p);
    }
  return hi ? up : lo;
}

TEST(SceneSamples, AllLoadAndFlatten) {
  for (const char* name : {"cornell.json", "furnace.json", "sky_plane.json", "features_zoo.json"}) {
    Scene s = load_scene(scene_path(name));
    FlatScene f = flatten(s, 0.0f);
    EXPECT_FALSE(f.triangles.empty()) << name;
    for (const GpuVertex& v : f.vertices) {
      ASSERT_TRUE(finite({v.px, v.py, v.pz})) << name;
      ASSERT_NEAR(length({v.nx, v.ny, v.nz}), 1.0f, 1e-4f) << name;
    }
  }
}

TEST(SceneSamples, FeaturesMatchIntent) {
  SceneFeatures cornell = load_scene(scene_path("cornell.json")).features();
  EXPECT_EQ(cornell, SceneFeatures(Feature::local_lights) | Feature::emissive) << to_string(cornell);
  EXPECT_EQ(load_scene(scene_path("furnace.json")).features(), SceneFeatures(Feature::sky));
  EXPECT_EQ(load_scene(scene_path("sky_plane.json")).features(), SceneFeatures(Feature::sky));
  EXPECT_EQ(load_scene(scene_path("furnace_glossy.json")).features(), SceneFeatures(Feature::sky) | Feature::glossy);
  // The zoo has every feature but glossy (the glossy BRDF class came after the tests whose
  // images the zoo's materials fix; furnace_glossy carries it).
  SceneFeatures zoo = load_scene(scene_path("features_zoo.json")).features();
  for (uint32_t i = 0; i < kFeatureCount; ++i) {
    Feature f = static_cast<Feature>(1u << i);
    if (f != Feature::glossy) {
      EXPECT_TRUE(zoo.has(f)) << feature_name(f);
    }
  }
}

TEST(SceneSamples, FurnaceIsWhiteOpenAndApart) {
  Scene s = load_scene(scene_path("furnace.json"));
  for (const Material& m : s.materials) EXPECT_EQ(m.albedo, (Vec3{1, 1, 1}));
  EXPECT_EQ(s.sky.kind, SkyKind::constant);
  EXPECT_EQ(s.sky.radiance, (Vec3{1, 1, 1}));
  EXPECT_TRUE(s.lights.empty());
  FlatScene f = flatten(s, 0.0f);
  ASSERT_EQ(f.instances.size(), 2u);
  Vec3 lo0 = world_extent_lo(f, 0, false), hi0 = world_extent_lo(f, 0, true);
  Vec3 lo1 = world_extent_lo(f, 1, false), hi1 = world_extent_lo(f, 1, true);
  Vec3 gap = vmax(lo1 - hi0, lo0 - hi1);
  EXPECT_GT(std::fmax(gap.x, std::fmax(gap.y, gap.z)), 4.0f);
  // Both objects are in front of the camera.
  Mat4 view = Mat4::look_at(s.camera.position, s.camera.target, s.camera.up);
  EXPECT_LT(view.transform_point((lo0 + hi0) * 0.5f).z, 0.0f);
  EXPECT_LT(view.transform_point((lo1 + hi1) * 0.5f).z, 0.0f);
}

// The degenerate-geometry case's scene holds every input it promises (docs/architecture.md).
TEST(SceneSamples, DegenerateHoldsTheDegenerateInputs) {
  Scene s = load_scene(scene_path("degenerate.json"));
  EXPECT_EQ(s.features(), SceneFeatures(Feature::sun) | Feature::sky | Feature::local_lights | Feature::textured)
      << to_string(s.features());
  EXPECT_EQ(s.lights.size(), 1u);
  const Mesh* mesh = nullptr;
  bool thin_slab = false;
  for (const Mesh& m : s.meshes) {
    if (m.name.rfind("mesh ", 0) == 0) mesh = &m;
    Vec3 e = bounds_extent(m);
    thin_slab = thin_slab || (m.name.rfind("thin_slab", 0) == 0 && std::fmin(e.x, std::fmin(e.y, e.z)) <= 1e-5f);
  }
  EXPECT_TRUE(thin_slab);
  ASSERT_NE(mesh, nullptr);
  size_t nan_normals = 0, zero_normals = 0, duplicates = 0, repeated_index = 0, collinear = 0;
  for (Vec3 n : mesh->normals) {
    nan_normals += std::isnan(n.x);
    zero_normals += n == Vec3{0, 0, 0};
  }
  for (size_t i = 0; i < mesh->positions.size(); ++i)
    for (size_t j = i + 1; j < mesh->positions.size(); ++j) duplicates += mesh->positions[i] == mesh->positions[j];
  for (size_t t = 0; t < mesh->indices.size() / 3; ++t) {
    uint32_t a = mesh->indices[3 * t], b = mesh->indices[3 * t + 1], c = mesh->indices[3 * t + 2];
    bool repeated = a == b || b == c || a == c;
    repeated_index += repeated;
    Vec3 g = cross(mesh->positions[b] - mesh->positions[a], mesh->positions[c] - mesh->positions[a]);
    collinear += !repeated && length(g) == 0.0f;
  }
  EXPECT_GE(nan_normals, 1u);
  EXPECT_GE(zero_normals, 1u);
  EXPECT_GE(duplicates, 1u);
  EXPECT_GE(repeated_index, 1u);
  EXPECT_GE(collinear, 1u);
  FlatScene f = flatten(s, 0.0f);
  for (const GpuVertex& v : f.vertices) ASSERT_TRUE(finite({v.px, v.py, v.pz}));
}

TEST(SceneSamples, SkyPlaneFillsTheView) {
  Scene s = load_scene(scene_path("sky_plane.json"));
  Mat4 inv = (Mat4::perspective(s.camera.fov_y_deg * kPi / 180.0f, 16.0f / 9.0f, s.camera.near_plane,
                                s.camera.far_plane) *
              Mat4::look_at(s.camera.position, s.camera.target, s.camera.up))
                 .inverse();
  for (float x : {-1.0f, 1.0f})
    for (float y : {-1.0f, 1.0f}) {
      Vec4 w = inv.transform({x, y, 1.0f, 1.0f});
      Vec3 dir = normalize(Vec3{w.x / w.w, w.y / w.w, w.z / w.w} - s.camera.position);
      ASSERT_LT(dir.y, 0.0f);
      float t = -s.camera.position.y / dir.y;
      Vec3 hit = s.camera.position + dir * t;
      EXPECT_LT(std::fabs(hit.x), 500.0f);
      EXPECT_LT(std::fabs(hit.z), 500.0f);
    }
}

}  // namespace
}  // namespace gib
