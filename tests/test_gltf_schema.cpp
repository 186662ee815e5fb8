// glTF as people write it: schema errors tinygltf would let through (one exact message per glTF
// object kind), strips and fans imported as triangles, points and lines skipped with a note,
// Draco-only meshes named, a scene made only of glTF objects, and the import report.
#include <gtest/gtest.h>

#include <functional>
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

std::string error_of(const GltfContent& g) {
  Scene s;
  try {
    import_gltf_bytes(s, test::to_glb(g), "bad.glb", ".", Mat4::identity());
  } catch (const SceneError& e) {
    EXPECT_TRUE(s.materials.empty() && s.meshes.empty() && s.instances.empty()) << "a failed import left content";
    return e.what();
  }
  return "<no error>";
}

std::string rich_error(const std::function<void(json&)>& edit) {
  GltfContent g = test::rich_content();
  edit(g.doc);
  return error_of(g);
}

// rich_content: 6 accessors, 6 bufferViews, 1 buffer, 4 materials, 2 meshes, 8 nodes, 1 scene,
// 1 texture, 1 image, 1 camera.
TEST(GltfSchema, WrongTypesAndIndicesNameThePointer) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& d) { d["asset"].erase("version"); }, "/asset/version: expected string, got missing key"},
      {[](json& d) { d["scene"] = "0"; }, "/scene: expected scene index in [0, 0], got \"0\""},
      {[](json& d) { d["scenes"][0]["nodes"] = {0, -1}; }, "/scenes/0/nodes/1: expected node index in [0, 7], got -1"},
      {[](json& d) { d["nodes"][1]["rotation"] = "x"; }, "/nodes/1/rotation: expected array of 4 numbers, got \"x\""},
      {[](json& d) { d["nodes"][0]["children"] = {1, 8}; }, "/nodes/0/children/1: expected node index in [0, 7], got 8"},
      {[](json& d) { d["nodes"][0]["extensions"] = json::array(); }, "/nodes/0/extensions: expected object, got empty array"},
      {[](json& d) { d["meshes"][0]["primitives"] = d["meshes"][0]["primitives"][0]; },
       "/meshes/0/primitives: expected non-empty array of objects, got object"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = "0"; },
       "/meshes/0/primitives/0/attributes/POSITION: expected accessor index in [0, 5], got \"0\""},
      {[](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 7; },
       "/meshes/0/primitives/0/mode: expected integer in [0, 6], got 7"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["material"] = -1; },
       "/meshes/0/primitives/0/material: expected material index in [0, 3], got -1"},
      {[](json& d) { d["accessors"][0]["count"] = "3"; }, "/accessors/0/count: expected integer >= 1, got \"3\""},
      {[](json& d) { d["accessors"][0].erase("type"); }, "/accessors/0/type: expected string, got missing key"},
      {[](json& d) { d["bufferViews"][0]["buffer"] = 1; }, "/bufferViews/0/buffer: expected buffer index in [0, 0], got 1"},
      {[](json& d) { d["buffers"][0].erase("byteLength"); }, "/buffers/0/byteLength: expected integer >= 1, got missing key"},
      {[](json& d) { d["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", "2"}}; },
       "/materials/0/normalTexture/scale: expected number, got \"2\""},
      {[](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = -1; },
       "/materials/0/pbrMetallicRoughness/baseColorTexture/index: expected texture index in [0, 0], got -1"},
      {[](json& d) { d["materials"][1]["emissiveFactor"] = {1, 1}; },
       "/materials/1/emissiveFactor: expected array of 3 numbers, got array of 2 elements"},
      {[](json& d) { d["textures"][0]["source"] = 3; }, "/textures/0/source: expected image index in [0, 0], got 3"},
      {[](json& d) { d["images"][0]["uri"] = 5; }, "/images/0/uri: expected string, got 5"},
      {[](json& d) { d["samplers"] = {{{"wrapS", "REPEAT"}}}; }, "/samplers/0/wrapS: expected integer >= 0, got \"REPEAT\""},
      {[](json& d) { d["textures"][0]["sampler"] = 0; }, "/textures/0/sampler: expected sampler index (the file has no samplers), got 0"},
      {[](json& d) { d["cameras"][0]["perspective"].erase("yfov"); },
       "/cameras/0/perspective/yfov: expected number, got missing key"},
      {[](json& d) { d["skins"] = {{{"joints", 0}}}; }, "/skins/0/joints: expected array of node indices, got 0"},
      {[](json& d) { d["animations"] = {{{"channels", json::array()}, {"samplers", json::array()}}}; },
       "/animations/0/channels: expected non-empty array of objects, got empty array"},
      {[](json& d) { d["extensionsUsed"] = "KHR_lights_punctual"; },
       "/extensionsUsed: expected array of strings, got \"KHR_lights_punctual\""},
  };
  for (const auto& [edit, message] : cases) EXPECT_EQ(rich_error(edit), "bad.glb: " + message);
}

// ---------------------------------------------------------------- primitive modes

// Five vertices in a zigzag, x = 0, 0, 1, 1, 2 and y = 0, 1, 0, 1, 0 (a strip's order), one
// primitive of `mode` drawing them, indexed by u16 indices `order` (none: in order).
GltfContent five_vertices(int mode, const std::vector<uint16_t>& order = {}) {
  GltfContent g;
  g.doc = {{"asset", {{"version", "2.0"}}}};
  const float pos[15] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0};
  json prim = {{"attributes", {{"POSITION", g.add(pos, 5, test::kFloat, "VEC3", 12)}}}, {"mode", mode}};
  if (!order.empty()) prim["indices"] = g.add(order.data(), order.size(), test::kU16, "SCALAR", 2);
  g.doc["meshes"] = {{{"primitives", {prim}}}};
  g.doc["nodes"] = {{{"mesh", 0}}};
  g.doc["scenes"] = {{{"nodes", {0}}}};
  return g;
}

std::vector<uint32_t> imported_indices(const GltfContent& g) {
  Scene s;
  import_gltf_bytes(s, test::to_glb(g), "modes.glb", ".", Mat4::identity());
  EXPECT_EQ(s.instances.size(), 1u);
  return s.instances.empty() ? std::vector<uint32_t>{} : s.meshes[s.instances[0].mesh].indices;
}

// Every triangle's face normal (right-handed winding) must be the first one's.
void expect_one_winding(const GltfContent& g, const std::vector<uint32_t>& idx, float z) {
  const float* p = reinterpret_cast<const float*>(g.bin.data());
  for (size_t t = 0; t < idx.size(); t += 3) {
    const float* a = p + 3 * idx[t];
    const float* b = p + 3 * idx[t + 1];
    const float* c = p + 3 * idx[t + 2];
    const float nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_EQ(nz, z) << "triangle " << t / 3;
  }
}

TEST(GltfModes, StripIsTrianglesWithOneWinding) {
  const GltfContent g = five_vertices(5);
  const std::vector<uint32_t> idx = imported_indices(g);
  EXPECT_EQ(idx, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));  // 3 triangles, the odd one reordered
  expect_one_winding(g, idx, -1.0f);
  const GltfContent indexed = five_vertices(5, {4, 3, 2, 1});  // (4,3,2) and (3,1,2)
  EXPECT_EQ(imported_indices(indexed), (std::vector<uint32_t>{4, 3, 2, 3, 1, 2}));
}

TEST(GltfModes, FanIsTrianglesAroundTheFirstVertex) {
  const GltfContent g = five_vertices(6, {2, 4, 3, 1, 0});
  const std::vector<uint32_t> idx = imported_indices(g);
  EXPECT_EQ(idx, (std::vector<uint32_t>{4, 3, 2, 3, 1, 2, 1, 0, 2}));  // 3 triangles
  expect_one_winding(g, idx, 1.0f);
}

TEST(GltfModes, TooFewVerticesForAStripIsAnError) {
  GltfContent g = five_vertices(6, {0, 1});
  EXPECT_EQ(error_of(g),
            "bad.glb: /meshes/0/primitives/0/indices: expected at least 3 indices (TRIANGLE_FAN), got 2 in /accessors/1");
}

TEST(GltfModes, PointsAndLinesAreSkippedWithANote) {
  GltfContent g = test::triangle_content();
  json prim = g.doc["meshes"][0]["primitives"][0];
  for (int mode : {0, 1, 2, 3}) {
    prim["mode"] = mode;
    g.doc["meshes"][0]["primitives"].push_back(prim);
  }
  Scene s;
  const GltfImportReport r = import_gltf_bytes(s, test::to_glb(g), "lines.glb", ".", Mat4::identity());
  EXPECT_EQ(r.instance_count, 1u);
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_EQ(r.notes, (std::vector<std::string>{
                         "/meshes/0/primitives/1: POINTS skipped (points and lines cannot be shaded)",
                         "/meshes/0/primitives/2: LINES skipped (points and lines cannot be shaded)",
                         "/meshes/0/primitives/3: LINE_LOOP skipped (points and lines cannot be shaded)",
                         "/meshes/0/primitives/4: LINE_STRIP skipped (points and lines cannot be shaded)"}));
}

// ---------------------------------------------------------------- extensions

// The triangle whose POSITION exists only as Draco data: its accessor has no bufferView.
GltfContent draco_triangle(bool required, bool fallback) {
  GltfContent g = test::triangle_content();
  g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  if (required) g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  g.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 0}, {"attributes", {{"POSITION", 0}}}};
  if (!fallback) g.doc["accessors"][0].erase("bufferView");
  return g;
}

TEST(GltfExtensions, DracoIsNamed) {
  EXPECT_EQ(error_of(draco_triangle(true, false)),
            "bad.glb: /extensionsRequired/0: expected a required extension gibench supports (KHR_lights_punctual, "
            "KHR_materials_emissive_strength), got \"KHR_draco_mesh_compression\" (Draco-compressed meshes are not supported)");
  EXPECT_EQ(error_of(draco_triangle(false, false)),
            "bad.glb: /meshes/0/primitives/0/extensions/KHR_draco_mesh_compression: expected uncompressed vertex data "
            "beside it (KHR_draco_mesh_compression is not supported), got /accessors/0 without a bufferView (its data "
            "only in Draco form)");
  // Optional Draco beside the uncompressed data: the data is read, the extension noted.
  Scene s;
  const GltfImportReport r = import_gltf_bytes(s, test::to_glb(draco_triangle(false, true)), "d.glb", ".", Mat4::identity());
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_EQ(r.notes, (std::vector<std::string>{"extension KHR_draco_mesh_compression (optional) ignored"}));
}

TEST(GltfExtensions, UnsupportedRequiredExtensionRefusesTheFile) {
  GltfContent g = test::triangle_content();
  g.doc["extensionsRequired"] = {"KHR_texture_transform"};
  EXPECT_EQ(error_of(g), "bad.glb: /extensionsRequired/0: expected a required extension gibench supports "
                         "(KHR_lights_punctual, KHR_materials_emissive_strength), got \"KHR_texture_transform\"");
}

// ---------------------------------------------------------------- the scene file and the report

// What the viewer shows and the import does not: optional extensions, TANGENT, a second UV set,
// a clamping sampler.
GltfContent partly_read() {
  GltfContent g = test::rich_content();
  g.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_clearcoat", "KHR_texture_transform"};
  g.doc["materials"][0]["extensions"]["KHR_materials_clearcoat"] = {{"clearcoatFactor", 1}};
  const float tangents[12] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  g.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = g.add(tangents, 3, test::kFloat, "VEC4", 16);
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
  g.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 10497}}};
  g.doc["textures"][0]["sampler"] = 0;
  return g;
}

TEST(GltfScene, GltfOnlySceneNeedsNoMaterialsAndKeepsTheReport) {
  test::TempDir dir;
  const std::vector<uint8_t> glb = test::to_glb(partly_read());
  dir.write("part.glb", std::string(glb.begin(), glb.end()));
  const std::string path = dir.write("only.json", R"({"objects": [{"type": "gltf", "name": "p", "file": "part.glb"}]})");
  const Scene s = load_scene(path);
  EXPECT_EQ(s.instances.size(), 4u);
  EXPECT_EQ(s.materials.size(), 5u);  // the file's four and glTF's default, nothing else
  ASSERT_EQ(s.imports.size(), 1u);
  EXPECT_EQ(s.imports[0].file, dir.str() + "/part.glb");
  EXPECT_EQ(s.imports[0].read,
            "3 meshes, 4 instances (6 triangles, 18 vertices), 5 materials, 1 textures (0.0 KiB with mips), 2 lights, the "
            "camera, the sun");
  EXPECT_EQ(s.imports[0].ignored,
            (std::vector<std::string>{"extension KHR_materials_clearcoat (optional) ignored",
                                      "extension KHR_texture_transform (optional) ignored",
                                      "/samplers/0: wrap modes other than REPEAT sampled as REPEAT",
                                      "/materials/0/pbrMetallicRoughness/baseColorTexture: TEXCOORD_1 read as TEXCOORD_0",
                                      "attribute TANGENT ignored"}));

  // A primitive object still needs the library it names a material from.
  const std::string prim = dir.write("prim.json", R"({"objects": [{"primitive": {"type": "quad"}, "material": "white"}]})");
  std::string msg;
  try { load_scene(prim); } catch (const SceneError& e) { msg = e.what(); }
  EXPECT_EQ(msg, prim + ": /materials: expected non-empty object of materials (primitive objects name one), got missing key");
}

}  // namespace
}  // namespace gib
