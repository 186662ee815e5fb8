// Internal to the glTF import (gltf_model.cpp): the checks made on the parsed JSON before
// tinygltf reads it. tinygltf skips what it does not understand (a `primitives` object instead
// of an array gives an empty mesh, a string texture `scale` keeps the default, a negative
// texture index means "none"), so the types, required properties and indices of glTF 2.0's
// schema are checked here, each failure one line naming the JSON pointer:
// `<file>: /meshes/0/primitives: expected non-empty array of objects, got object`.
#pragma once
#include <nlohmann/json.hpp>
#include <string_view>

#include "renderer/scene/gltf_model.h"

namespace gib::gltf {

// The extensions the import reads; every other one in extensionsUsed is reported as ignored.
bool supported_extension(std::string_view name);

// Every core object's properties the import or the schema constrains: JSON types, required
// properties, integer minimums, array lengths, and indices into the document's arrays.
// Properties the table does not name (extras, extension contents) are not checked here.
void check_schema(const nlohmann::json& doc, const Where& where);

// extensionsRequired holds only supported extensions; a mesh stored only as
// KHR_draco_mesh_compression data (its accessors without a bufferView) is named as such.
void check_extensions(const nlohmann::json& doc, const Where& where);

}  // namespace gib::gltf
