// glTF import: known answers for the node tree, materials, lights and camera;
// one test per class of bad input; the scene file's "gltf" objects.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/scene/gltf_import.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gltf_test_content.h"
#include "tests/temp_dir.h"

namespace gib {
namespace {

using json = nlohmann::json;
using test::GltfContent;

void expect_near(Vec3 a, Vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

Vec3 vertex(const FlatScene& f, uint32_t triangle, int corner) {
  const GpuTriangle& t = f.triangles[triangle];
  const GpuVertex& v = f.vertices[corner == 0 ? t.i0 : corner == 1 ? t.i1 : t.i2];
  return {v.px, v.py, v.pz};
}

std::string import_error(const std::vector<uint8_t>& bytes, const std::string& name = "bad.glb",
                         const std::string& base = ".") {
  Scene s;
  try {
    import_gltf_bytes(s, bytes, name, base, Mat4::identity());
  } catch (const SceneError& e) {
    EXPECT_TRUE(s.materials.empty() && s.meshes.empty() && s.instances.empty()) << "a failed import left content";
    return e.what();
  }
  return "<no error>";
}

// The message names the file, has the "expected ..., got ..." form and holds `fragment`.
void expect_error(const std::string& msg, const std::string& file, const std::string& fragment) {
  EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
  EXPECT_NE(msg.find("expected "), std::string::npos) << msg;
  EXPECT_NE(msg.find(", got "), std::string::npos) << msg;
  EXPECT_NE(msg.find(fragment), std::string::npos) << msg << "\n  wanted: " << fragment;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  if (std::getenv("GIB_PRINT_SCENE_ERRORS")) std::printf("%s\n", msg.c_str());
}

TEST(GltfImport, HierarchyTransformsAndInstances) {
  Scene s;
  const GltfImportReport r =
      import_gltf_bytes(s, test::to_glb(test::rich_content()), "rich.glb", ".", Mat4::translation({0, 10, 0}));
  ASSERT_EQ(s.instances.size(), 4u);  // spun (tri), moved (2 primitives), again (tri)
  EXPECT_EQ(r.instance_count, 4u);
  EXPECT_EQ(r.mesh_count, 3u);  // the triangle is shared by "spun" and "again"
  EXPECT_EQ(s.instances[0].name, "rich/spun");
  EXPECT_EQ(s.instances[1].name, "rich/moved/0");
  EXPECT_EQ(s.instances[3].mesh, s.instances[0].mesh);
  const FlatScene f = flatten(s, 0.0f);
  // spun: root translate (1,0,0) * rotate 90 degrees about Y * scale 2, under the object's (0,10,0).
  expect_near(vertex(f, 0, 0), {1, 10, 0});
  expect_near(vertex(f, 0, 1), {1, 10, -2});  // (1,0,0) -> (2,0,0) -> (0,0,-2) -> (1,10,-2)
  expect_near(vertex(f, 0, 2), {1, 12, 0});
  expect_near({f.vertices[f.triangles[0].i0].nx, f.vertices[f.triangles[0].i0].ny, f.vertices[f.triangles[0].i0].nz}, {1, 0, 0});
  // moved: matrix translation (0,3,0) under root: the quad's (1,1,0) lands at (2,14,0).
  expect_near(vertex(f, 1, 2), {2, 14, 0});
  // again: identity under the object transform only.
  expect_near(vertex(f, f.instances[3].first_triangle, 1), {1, 10, 0});
  // The non-indexed quad has no normals: zero (shading takes the face normal).
  EXPECT_TRUE(s.meshes[s.instances[1].mesh].normals.empty());
  EXPECT_EQ(s.meshes[s.instances[1].mesh].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(GltfImport, MaterialsMapToTheSceneModel) {
  Scene s;
  s.materials.push_back(Material{"rich/red"});  // an existing name: the import must not reuse it
  const GltfImportReport r = import_gltf_bytes(s, test::to_glb(test::rich_content()), "rich.glb", ".", Mat4::identity());
  ASSERT_EQ(s.materials.size(), 6u);  // the library's, 4 glTF materials, the default one
  EXPECT_EQ(r.first_material, 1u);
  const Material& red = s.materials[1];
  EXPECT_EQ(red.name, "rich/red#2");
  EXPECT_EQ(red.albedo, (Vec3{1, 0, 0}));
  EXPECT_EQ(red.metalness, 0.0f);
  EXPECT_EQ(red.roughness, 0.5f);
  const Material& glass = s.materials[2];
  EXPECT_EQ(glass.alpha, AlphaKind::opacity);
  EXPECT_EQ(glass.opacity, 0.25f);
  EXPECT_EQ(s.materials[3].emissive, (Vec3{4, 2, 1}));  // emissiveFactor x emissiveStrength
  EXPECT_EQ(s.materials[3].metalness, 1.0f);           // glTF's default metallicFactor
  const Material& cutout = s.materials[4];             // MASK, alpha 0.3 below cutoff 0.6: invisible
  EXPECT_EQ(cutout.alpha, AlphaKind::opacity);
  EXPECT_EQ(cutout.opacity, 0.0f);
  EXPECT_EQ(cutout.alpha_cutoff, 0.6f);
  EXPECT_EQ(s.materials[5].name, "rich/default");
  EXPECT_EQ(s.materials[5].albedo, (Vec3{1, 1, 1}));
  EXPECT_EQ(s.instances[2].material, 5u);
  // Used materials decide the features: glass (alpha), lamp (emissive); cutout is unused.
  const SceneFeatures feat = s.features();
  EXPECT_TRUE(feat.has(Feature::emissive));
  EXPECT_TRUE(feat.has(Feature::alpha_tested));
  EXPECT_TRUE(feat.has(Feature::local_lights));
  EXPECT_TRUE(feat.has(Feature::sun));
  EXPECT_FALSE(feat.has(Feature::textured));  // the textured material (0) is not used
  EXPECT_EQ(r.materials[0].textures.base_color, 0);
  EXPECT_EQ(r.materials[0].scene_material, 1u);
  EXPECT_EQ(r.materials[1].textures.base_color, -1);

  GltfContent mask = test::triangle_content();  // MASK with alpha above the cutoff: opaque
  mask.doc["materials"][0]["alphaMode"] = "MASK";
  Scene m;
  import_gltf_bytes(m, test::to_glb(mask), "mask.glb", ".", Mat4::identity());
  EXPECT_EQ(m.materials[0].alpha, AlphaKind::none);
  EXPECT_FALSE(m.features().has(Feature::alpha_tested));
}

TEST(GltfImport, LightsSunAndCamera) {
  Scene s;
  const GltfImportReport r = import_gltf_bytes(s, test::to_glb(test::rich_content()), "rich.glb", ".", Mat4::identity());
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(r.lights, 2u);
  const LocalLight& point = s.lights[0];
  EXPECT_EQ(point.kind, LightKind::point);
  expect_near(point.position, {1, 5, 0});  // root (1,0,0) + moved (0,3,0) + bulb (0,2,0)
  EXPECT_EQ(point.intensity, (Vec3{10, 5, 0}));  // colour x candela -> W/sr one to one
  EXPECT_EQ(point.range, 7.0f);
  const LocalLight& spot = s.lights[1];
  EXPECT_EQ(spot.kind, LightKind::spot);
  expect_near(spot.direction, {0, -1, 0});  // -Z turned down by -90 degrees about X
  EXPECT_EQ(spot.range, LocalLight{}.range);  // no range: the scene's default
  EXPECT_NEAR(spot.inner_cone_deg, 0.25 * 180 / M_PI, 1e-4);
  EXPECT_NEAR(spot.outer_cone_deg, 0.5 * 180 / M_PI, 1e-4);
  ASSERT_TRUE(s.sun.enabled);
  expect_near(s.sun.direction, {0, std::sqrt(0.5f), std::sqrt(0.5f)});
  EXPECT_EQ(s.sun.irradiance, (Vec3{2, 2, 2}));
  ASSERT_TRUE(r.camera);
  expect_near(s.camera.position, {0, 1, 5});
  expect_near(normalize(s.camera.target - s.camera.position), {0, 0, -1});
  EXPECT_NEAR(s.camera.fov_y_deg, 0.8 * 180 / M_PI, 1e-4);
  EXPECT_EQ(s.camera.far_plane, 50.0f);

  Scene own;  // the scene sets camera and sun: nothing taken, directional lights ignored
  GltfImportOptions opt;
  opt.take_camera = opt.take_sun = false;
  const GltfImportReport r2 = import_gltf_bytes(own, test::to_glb(test::rich_content()), "rich.glb", ".", Mat4::identity(), opt);
  EXPECT_FALSE(r2.camera);
  EXPECT_FALSE(own.sun.enabled);
  EXPECT_EQ(own.camera.position, Camera{}.position);
}

TEST(GltfErrors, EachClassNamesTheFileAndWhatWasExpected) {
  test::TempDir dir;
  auto glb_error = [&](const std::function<void(GltfContent&)>& edit) {
    GltfContent g = test::rich_content();
    edit(g);
    return import_error(test::to_glb(g));
  };
  // A missing buffer file (.gltf with an external buffer).
  const std::string gltf = dir.str() + "/missing.gltf";
  std::vector<uint8_t> text = test::to_gltf(test::triangle_content(), "gone.bin");
  std::ofstream(gltf, std::ios::binary).write(reinterpret_cast<const char*>(text.data()), std::streamsize(text.size()));
  Scene s;
  std::string msg;
  try { import_gltf(s, gltf, Mat4::identity()); } catch (const SceneError& e) { msg = e.what(); }
  expect_error(msg, gltf, "/buffers/0/uri: expected a readable buffer file (relative to the glTF file), got \"gone.bin\"");
  // An accessor out of range of its buffer view.
  expect_error(glb_error([](GltfContent& g) { g.doc["accessors"][0]["count"] = 4; }), "bad.glb",
               "/accessors/0: expected elements inside bufferView 0");
  expect_error(glb_error([](GltfContent& g) { g.doc["bufferViews"][1]["byteOffset"] = 1u << 30; }), "bad.glb",
               "/bufferViews/1: expected a byte range inside buffer 0");
  // A required extension the import does not support.
  expect_error(glb_error([](GltfContent& g) { g.doc["extensionsRequired"] = json::array({"KHR_lights_punctual", "KHR_draco_mesh_compression"}); }),
               "bad.glb", "/extensionsRequired/1: expected a required extension gibench supports");
  // A mode glTF does not define (0-3 are skipped, 4-6 imported: test_gltf_schema.cpp).
  expect_error(glb_error([](GltfContent& g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 7; }), "bad.glb",
               "/meshes/0/primitives/0/mode: expected integer in [0, 6], got 7");
  // Corrupt JSON and a truncated .glb.
  std::vector<uint8_t> corrupt = test::to_gltf(test::triangle_content());
  corrupt.resize(corrupt.size() / 2);
  expect_error(import_error(corrupt, "corrupt.gltf"), "corrupt.gltf", "expected a valid glTF 2.0 JSON file");
  std::vector<uint8_t> cut = test::to_glb(test::rich_content());
  cut.resize(cut.size() - 40);
  expect_error(import_error(cut), "bad.glb", "(a truncated file)");
  std::vector<uint8_t> chunk = test::to_glb(test::rich_content());
  chunk[13] = 0xff;  // the JSON chunk's length past the end
  expect_error(import_error(chunk), "bad.glb", "expected a JSON chunk inside the file");
  // Indices past the vertices, absurd counts, a node reached twice, bad numbers and references.
  expect_error(glb_error([](GltfContent& g) { g.bin[36 * 2 + 24 + 2] = 7; }), "bad.glb",
               "/meshes/0/primitives/0/indices: expected vertex indices below 3 (the POSITION count), got 7");
  expect_error(glb_error([](GltfContent& g) { g.doc["accessors"][0]["count"] = 1ull << 40; }), "bad.glb",
               "/accessors/0/count: expected integer in [1, 67108864]");
  expect_error(glb_error([](GltfContent& g) { g.doc["nodes"][7]["children"] = json::array({0}); }), "bad.glb",
               "/nodes/7/children/0: expected a node not yet in the scene's hierarchy");
  expect_error(glb_error([](GltfContent& g) { g.doc["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 2; }),
               "bad.glb", "/materials/0/pbrMetallicRoughness/metallicFactor: expected number in [0, 1], got 2");
  expect_error(glb_error([](GltfContent& g) { g.doc["nodes"][1]["mesh"] = 9; }), "bad.glb",
               "/nodes/1/mesh: expected mesh index in [0, 1], got 9");
  expect_error(glb_error([](GltfContent& g) { g.doc["nodes"][1]["matrix"] = json::array({1, 2}); }), "bad.glb",
               "/nodes/1/matrix: expected array of 16 numbers");
  expect_error(glb_error([](GltfContent& g) { g.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "area"; }),
               "bad.glb", "/extensions/KHR_lights_punctual/lights/0/type: expected one of \"point\", \"spot\", \"directional\"");
  expect_error(glb_error([](GltfContent& g) { g.doc["nodes"][7]["extensions"]["KHR_lights_punctual"]["light"] = 2; }),
               "bad.glb", "expected at most one directional light in the scene");
  expect_error(glb_error([](GltfContent& g) { g.doc["asset"]["version"] = "1.0"; }), "bad.glb", "/asset/version");
  // extras.gibench_solid must be a boolean (Instance::solid).
  expect_error(glb_error([](GltfContent& g) { g.doc["nodes"][1]["extras"] = {{"gibench_solid", "yes"}}; }), "bad.glb",
               "/nodes/1/extras/gibench_solid: expected a boolean, got another type");
  // A texture whose image file is missing, and one that cannot be decoded.
  expect_error(glb_error([](GltfContent& g) {
                 g.doc["images"] = {{{"uri", "nowhere.png"}}};
                 g.doc["textures"] = {{{"source", 0}}};
                 g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
               }),
               "bad.glb", "/images/0/uri: expected a readable image file");
  expect_error(glb_error([](GltfContent& g) {
                 g.doc["images"] = {{{"bufferView", 0}, {"mimeType", "image/png"}}};
                 g.doc["textures"] = {{{"source", 0}}};
                 g.doc["materials"][1]["emissiveTexture"] = {{"index", 0}};
               }),
               "bad.glb", "/images/0: expected an image stb_image can decode");
}

// ---------------------------------------------------------------- the scene file's key

std::string write_bytes(const test::TempDir& dir, const std::string& name, const std::vector<uint8_t>& bytes) {
  return dir.write(name, std::string(bytes.begin(), bytes.end()));
}

TEST(GltfScene, ObjectsImportFilesRelativeToTheScene) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path() / "models");
  write_bytes(dir, "models/rich.glb", test::to_glb(test::rich_content()));
  const std::string scene = dir.write("scene.json", R"({
    "materials": {"white": {}},
    "objects": [{"primitive": {"type": "quad", "size": [10, 10]}, "material": "white"},
                {"type": "gltf", "name": "court", "file": "models/rich.glb", "transform": {"translate": [0, 10, 0]}}]})");
  Scene s = load_scene(scene);
  ASSERT_EQ(s.instances.size(), 5u);
  EXPECT_EQ(s.instances[1].name, "court/spun");
  EXPECT_EQ(s.materials[1].name, "rich/red");
  expect_near(s.camera.position, {0, 11, 5});  // the scene has no camera: the file's, moved with it
  EXPECT_TRUE(s.sun.enabled);
  EXPECT_EQ(s.lights.size(), 2u);
  expect_near(vertex(flatten(s, 0), 2, 2), {1, 12, 0});

  // The scene's own camera and sun win.
  const std::string own = dir.write("own.json", R"({
    "materials": {"white": {}}, "camera": {"position": [0, 2, 9]},
    "sun": {"direction": [0, 1, 0], "irradiance": [1, 1, 1]},
    "objects": [{"type": "gltf", "file": "models/rich.glb"}]})");
  Scene o = load_scene(own);
  EXPECT_EQ(o.camera.position, (Vec3{0, 2, 9}));
  EXPECT_EQ(o.sun.direction, (Vec3{0, 1, 0}));
  EXPECT_EQ(o.instances[0].name, "object0/spun");

  // Two imports of a file with a directional light and no scene sun: two suns, an error.
  const std::string twice = dir.write("twice.json", R"({"materials": {"white": {}},
    "objects": [{"type": "gltf", "file": "models/rich.glb"}, {"type": "gltf", "file": "models/rich.glb"}]})");
  std::string msg;
  try { load_scene(twice); } catch (const SceneError& e) { msg = e.what(); }
  expect_error(msg, (dir.path() / "models/rich.glb").string(), "at most one directional light");
}

TEST(GltfScene, ObjectKeyErrorsNameTheSceneFile) {
  test::TempDir dir;
  auto error_of = [&](const std::string& objects) {
    const std::string path = dir.write("s.json", R"({"materials": {"white": {}}, "objects": )" + objects + "}");
    try { load_scene(path); } catch (const SceneError& e) { return std::string(e.what()); }
    return std::string("<no error>");
  };
  const std::string scene = dir.str() + "/s.json";
  expect_error(error_of(R"([{"type": "gltf", "file": "nope.glb"}])"), scene, "/objects/0/file: expected a .gltf or .glb file");
  expect_error(error_of(R"([{"type": "gltf"}])"), scene, "/objects/0/file: expected string, got missing key");
  expect_error(error_of(R"([{"type": "gltf", "file": "x.glb", "material": "white"}])"), scene, "/objects/0/material: expected one of the keys");
  expect_error(error_of(R"([{"type": "mesh", "file": "x.glb"}])"), scene, "/objects/0/type: expected one of \"primitive\", \"gltf\"");
}

}  // namespace
}  // namespace gib
