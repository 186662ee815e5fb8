// glTF 2.0 import: appends a .gltf/.glb file's default scene to a Scene.
// The scene key that uses it ({"type": "gltf", "file": ...}) and its rules are documented in
// cases/scenes/README.md, section "glTF objects".
//
// What is imported: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (indexed or not; strips
// and fans become triangle lists) with POSITION, NORMAL and TEXCOORD_0 (points and lines are
// skipped, noted in the report);
// the default scene's node tree (matrix or TRS, composed with the object's transform: one
// Instance per primitive per node); metallic-roughness material factors; KHR_lights_punctual
// point and spot lights (directional -> the scene's sun); KHR_materials_emissive_strength;
// the first perspective camera; base colour (sRGB, its alpha for MASK/BLEND), emissive (sRGB)
// and metallic-roughness (linear) textures, decoded with stb_image into Scene::textures with their
// mips (one texture per image and colour space). Not imported: normal and occlusion textures
// (checked to decode, recorded in GltfImportReport), samplers other than REPEAT (sampled as
// REPEAT), TEXCOORD_n for n > 0, skins, morph targets, animations, sparse accessors.
//
// Units: glTF and the scene are both metres, +Y up, right-handed. Photometric glTF values map
// one to one onto the scene's radiometric ones (see gltf_importer.h, "Units").
//
// Every problem is one SceneError line naming the glTF file and, where it has one, the JSON
// pointer inside it: `<file>: <pointer>: expected <what>, got <what>`. The JSON is checked
// against glTF 2.0's schema (types, required properties, indices) before tinygltf reads it
// (gltf_schema.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/math.h"
#include "renderer/scene/scene.h"

namespace gib {

struct GltfImportOptions {
  std::string material_prefix;  // imported material names start with it; empty: "<file stem>/"
  std::string instance_prefix;  // instance names start with it; empty: "<file stem>/"
  bool take_camera = true;      // the first perspective camera becomes Scene::camera
  // true: the first directional light becomes Scene::sun, and a second one in the scene (this
  // file or an earlier import: Scene::sun already enabled) is an error; false: the scene sets
  // its own sun and every directional light is ignored.
  bool take_sun = true;
};

// Texture indices a material references (-1: none); normal and occlusion are not sampled.
struct GltfTextureRefs {
  int base_color = -1, metallic_roughness = -1, emissive = -1, normal = -1, occlusion = -1;
};

struct GltfMaterialInfo {
  uint32_t scene_material = 0;  // index into Scene::materials
  bool double_sided = false;    // glTF doubleSided (every surface is two-sided here regardless)
  GltfTextureRefs textures;
};

struct GltfImportReport {
  std::string path;
  uint32_t first_material = 0, material_count = 0;  // Scene::materials added
  uint32_t first_mesh = 0, mesh_count = 0;          // Scene::meshes added
  uint32_t first_instance = 0, instance_count = 0;  // Scene::instances added
  uint64_t triangles = 0, vertices = 0;             // instanced (what flatten produces)
  uint32_t lights = 0;                              // LocalLights added
  uint32_t first_texture = 0, texture_count = 0;    // Scene::textures added
  uint64_t texture_bytes = 0;                       // theirs, every mip level
  bool camera = false, sun = false;                 // Scene::camera / Scene::sun set
  std::vector<GltfMaterialInfo> materials;          // one per glTF material (then the default one)
  std::vector<std::string> notes;                   // content present but not imported
};

// The report as the scene keeps it: what was read (one line) and what was ignored.
SceneImport scene_import(const GltfImportReport& report);

// Limits on what one import may add (absurd counts are errors, not allocations).
inline constexpr uint64_t kGltfMaxTriangles = 1ull << 24;     // instanced, per import
inline constexpr uint64_t kGltfMaxVertices = 3ull << 24;      // instanced, per import
inline constexpr uint64_t kGltfMaxAccessorCount = 1ull << 26;  // elements of one accessor

// Reads `path` (.gltf with its buffers, or .glb: told apart by the content, not the name) and
// appends its default scene, placed by `transform`.
GltfImportReport import_gltf(Scene& scene, const std::string& path, const Mat4& transform,
                             const GltfImportOptions& options = {});

// The same from bytes already in memory: `name` is what messages call the file, `base_dir`
// where relative buffer and image URIs are found.
GltfImportReport import_gltf_bytes(Scene& scene, const std::vector<uint8_t>& bytes, const std::string& name,
                                   const std::string& base_dir, const Mat4& transform,
                                   const GltfImportOptions& options = {});

}  // namespace gib
