// glTF export and the round trip procedural scene -> glTF -> import: the flattened triangles
// (what every pass and the BVH consume) come back bit for bit, materials glTF can express come
// back equal, lights and camera within float rounding.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "renderer/scene/gltf_export.h"
#include "renderer/scene/gltf_import.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"
#include "tests/temp_dir.h"

namespace gib {
namespace {

std::string scene_path(const std::string& name) { return std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + name; }

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_near(Vec3 a, Vec3 b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// A material glTF carries completely (no procedural texture or mask, translucency or cloth).
bool expressible(const Material& m) {
  return m.texture == TextureKind::none && m.translucency == 0 && m.brdf == BrdfKind::standard &&
         (m.alpha == AlphaKind::none || m.alpha == AlphaKind::opacity);
}

void round_trip(const std::string& scene_file, const std::string& ext) {
  SCOPED_TRACE(scene_file + " as " + ext);
  const Scene original = load_scene(scene_path(scene_file));
  test::TempDir dir;
  const std::string path = dir.str() + "/" + std::filesystem::path(scene_file).stem().string() + ext;
  const GltfExportReport exported = export_gltf(original, path);
  EXPECT_EQ(exported.nodes, original.instances.size() + original.lights.size() + (exported.sun ? 1 : 0) + 1);
  if (ext == ".gltf") {
    EXPECT_TRUE(std::filesystem::exists(dir.path() / (std::filesystem::path(path).stem().string() + ".bin")));
  }

  Scene back;
  const GltfImportReport imported = import_gltf(back, path, Mat4::identity());
  ASSERT_EQ(back.instances.size(), original.instances.size());
  ASSERT_EQ(back.materials.size(), original.materials.size());
  const FlatScene a = flatten(original, 0.0f), b = flatten(back, 0.0f);
  EXPECT_TRUE(same_bytes(a.vertices, b.vertices)) << "vertices differ";
  EXPECT_TRUE(same_bytes(a.triangles, b.triangles)) << "triangles differ";
  EXPECT_TRUE(same_bytes(a.instances, b.instances)) << "instances differ";
  for (size_t i = 0; i < original.materials.size(); ++i) {
    const Material& m = original.materials[i];
    const Material& n = back.materials[i];
    EXPECT_EQ(n.name, std::filesystem::path(path).stem().string() + "/" + m.name);
    EXPECT_EQ(n.albedo, m.albedo) << m.name;
    EXPECT_EQ(n.roughness, m.roughness) << m.name;
    EXPECT_EQ(n.metalness, m.metalness) << m.name;
    EXPECT_EQ(n.emissive, m.emissive) << m.name;
    if (expressible(m)) {
      EXPECT_TRUE(std::memcmp(&a.materials[i], &b.materials[i], sizeof(GpuMaterial)) == 0) << m.name;
      EXPECT_EQ(n.alpha, m.alpha) << m.name;
      EXPECT_EQ(n.opacity, m.opacity) << m.name;
    }
  }
  ASSERT_EQ(back.lights.size(), original.lights.size());
  for (size_t i = 0; i < original.lights.size(); ++i) {
    const LocalLight& l = original.lights[i];
    const LocalLight& k = back.lights[i];
    EXPECT_EQ(k.kind, l.kind);
    EXPECT_EQ(k.position, l.position);
    EXPECT_EQ(k.intensity, l.intensity);  // colour x intensity, divided and multiplied in double
    EXPECT_EQ(k.range, l.range);
    if (l.kind == LightKind::spot) {
      expect_near(k.direction, l.direction, 1e-6f);
      EXPECT_NEAR(k.inner_cone_deg, l.inner_cone_deg, 1e-4f);
      EXPECT_NEAR(k.outer_cone_deg, l.outer_cone_deg, 1e-4f);
    }
  }
  const Sun sun = original.sun_at(0.0f);
  EXPECT_EQ(back.sun.enabled, sun.enabled);
  if (sun.enabled) {
    expect_near(back.sun.direction, sun.direction, 1e-6f);
    EXPECT_EQ(back.sun.irradiance, sun.irradiance);
  }
  const Camera cam = original.camera_at(0.0f);
  EXPECT_TRUE(imported.camera);
  expect_near(back.camera.position, cam.position, 1e-5f);
  expect_near(normalize(back.camera.target - back.camera.position), normalize(cam.target - cam.position), 1e-6f);
  EXPECT_NEAR(back.camera.fov_y_deg, cam.fov_y_deg, 1e-5f);
  EXPECT_EQ(back.camera.near_plane, cam.near_plane);
  EXPECT_EQ(back.camera.far_plane, cam.far_plane);
  EXPECT_EQ(back.features().has(Feature::local_lights), original.features().has(Feature::local_lights));
  EXPECT_EQ(back.features().has(Feature::emissive), original.features().has(Feature::emissive));
}

TEST(GltfRoundTrip, CornellIsBitIdentical) {
  round_trip("cornell.json", ".glb");
  round_trip("cornell.json", ".gltf");
}

// Spot light, animated box (exported at t = 0), leaf cards, cloth, decals: geometry still exact.
TEST(GltfRoundTrip, FeaturesZooGeometryIsBitIdentical) { round_trip("features_zoo.json", ".glb"); }

// NaN and zero normals, zero-area triangles, a collapsed instance, a 1e-5 m slab.
TEST(GltfRoundTrip, DegenerateInputSurvives) { round_trip("degenerate.json", ".gltf"); }

TEST(GltfRoundTrip, SunAndPointLightScenes) {
  round_trip("sun_sweep_arcade.json", ".glb");
  round_trip("room_point_light.json", ".glb");
}

TEST(GltfRoundTrip, LossyPartsAreReported) {
  const Scene zoo = load_scene(scene_path("features_zoo.json"));
  test::TempDir dir;
  const GltfExportReport r = export_gltf(zoo, dir.str() + "/zoo.glb");
  auto mentions = [&](const std::string& what) {
    for (const std::string& line : r.lossy)
      if (line.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(mentions("procedural alpha mask"));
  EXPECT_TRUE(mentions("procedural texture"));
  EXPECT_TRUE(mentions("cloth"));
  EXPECT_TRUE(mentions("translucency"));
  EXPECT_TRUE(mentions("animation"));
  EXPECT_TRUE(mentions("decal"));
  EXPECT_TRUE(mentions("sky"));
}

TEST(GltfRoundTrip, ExportErrorsNameThePath) {
  Scene s = load_scene(scene_path("cornell.json"));
  for (const std::string path : {"/nonexistent/dir/out.glb", "/nonexistent/dir/out.gltf"}) {
    try {
      export_gltf(s, path);
      ADD_FAILURE() << path << ": no error";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": expected a writable glTF file, got ", 0), 0u) << e.what();
    }
  }
  s.meshes[0].indices.clear();
  test::TempDir dir;
  try {
    export_gltf(s, dir.str() + "/empty.glb");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("whole triangles"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gib
