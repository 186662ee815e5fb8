// Internal to the glTF import (gltf_import.cpp): loading a file into a tinygltf::Model, the
// one-line error messages, and bounds-checked accessor reads. Nothing here trusts an index or a
// byte range of the file: every one is checked before it is used.
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/scene/math.h"

namespace gib::gltf {

// The file being imported, for messages: `<file>: <pointer>: expected <what>, got <what>`.
struct Where {
  std::string file;
  [[noreturn]] void fail(std::string_view pointer, std::string_view expected, std::string_view got) const;
  // A message about the whole file (no pointer): unreadable, not glTF, rejected by the parser.
  [[noreturn]] void fail_file(std::string_view expected, std::string_view got) const;
  // An index into an array of `count` elements; `what` names the array ("accessor", "node").
  size_t index(std::string_view pointer, int i, size_t count, std::string_view what) const;
  // A number from the file that must be finite as a float and lie in [lo, hi].
  float number(std::string_view pointer, double v, double lo, double hi) const;
};

// What the image callback saw of each image given by URI (images in a bufferView are read by
// the import once it has checked the view's range).
struct ImageLog {
  struct Entry {
    bool decodable = false;
    int width = 0, height = 0, channels = 0;
    std::string reason;  // why it cannot be decoded
    std::vector<uint8_t> bytes;  // the file's bytes (decoded by the import when a material uses it)
  };
  std::map<int, Entry> by_uri;  // image index -> what its bytes are
};
// Header-level check (stb_image's info): the format is known and the size readable.
ImageLog::Entry inspect_image(const unsigned char* bytes, size_t size);

// Parses .glb (by its magic) or .gltf bytes; external buffers and images are read relative to
// base_dir. Parser failures become one-line SceneErrors naming the file.
tinygltf::Model load_model(const std::vector<uint8_t>& bytes, const Where& where, const std::string& base_dir,
                           ImageLog& images);

// One accessor's elements, checked to lie inside its bufferView and buffer.
struct AccessorData {
  const uint8_t* data = nullptr;  // the first element, inside its buffer
  size_t stride = 0, count = 0;
  int component_type = 0, components = 0;
  bool normalized = false;
  std::string pointer;  // "/accessors/<i>"
  float get(size_t element, int component) const;      // converted (normalized integers / 2^n-1)
  uint32_t get_uint(size_t element) const;             // SCALAR unsigned integer types
};

// `ref` is where the index was read (e.g. "/meshes/0/primitives/1/attributes/POSITION");
// `type` a TINYGLTF_TYPE_*; `components` the allowed TINYGLTF_COMPONENT_TYPE_*s; `what` names
// the use in messages.
AccessorData accessor(const tinygltf::Model& m, int index, const Where& where, const std::string& ref, int type,
                      std::initializer_list<int> component_types, std::string_view what);
// Checks a bufferView's byte range against its buffer and returns its first byte.
const uint8_t* buffer_view_bytes(const tinygltf::Model& m, size_t view, const Where& where);

std::vector<Vec3> read_vec3(const AccessorData& a, bool require_finite, const Where& where);
std::vector<Vec2> read_vec2(const AccessorData& a, const Where& where);  // finite
std::vector<uint32_t> read_indices(const AccessorData& a, size_t vertex_count, const Where& where,
                                   const std::string& ref);

std::string component_type_name(int component_type);
std::string type_name(int type);

}  // namespace gib::gltf
