// glTF 2.0 export: writes a Scene's geometry, materials, lights and camera, so
// procedural scenes can be turned into glTF content and a round trip (export -> import_gltf)
// can be checked: the flattened triangles (flatten(): positions, normals, UVs, indices,
// instances) come back bit for bit.
//
// What glTF carries: one node per instance (its transform at `time`, as a matrix), one glTF
// mesh per (mesh, material) pair, float POSITION / NORMAL / TEXCOORD_0 and uint32 indices
// (a mesh without normals or UVs is written without them, as the import reads them back),
// metallic-roughness factors (albedo, metalness, roughness, emissive with
// KHR_materials_emissive_strength above 1, AlphaKind::opacity as BLEND with the opacity as
// base colour alpha), point and spot lights and the sun (KHR_lights_punctual, one to one
// units as the import), the camera (perspective), and image textures (Scene::textures, level 0
// as PNG in the binary buffer, lossless: base colour, emissive and metallic-roughness
// references, texture masks as MASK and texture opacity as BLEND with the factor alpha).
// What it cannot carry is listed in GltfExportReport::lossy: procedural textures (checker,
// value noise: albedo2, texture_scale), procedural alpha masks (written as MASK with base
// alpha 1, which imports opaque), translucency, the cloth BRDF and its sheen, every
// animation (written at `time`), the sun's angular radius, sky, decals, indoor volumes.
#pragma once
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace gib {

struct GltfExportReport {
  uint32_t meshes = 0, nodes = 0, materials = 0, lights = 0;
  bool sun = false, camera = false;
  // What the file does not carry, one line each; also normals that are not unit length or not
  // finite, written as they are (exact round trip) though glTF validators reject them.
  std::vector<std::string> lossy;
};

// `.glb` writes one binary file; any other name writes JSON glTF plus "<stem>.bin" beside it.
// Failures (a mesh without triangles, an unwritable path) are SceneErrors naming the path.
GltfExportReport export_gltf(const Scene& scene, const std::string& path, float time = 0.0f);

}  // namespace gib
