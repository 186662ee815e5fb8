// Small glTF files written by the tests themselves (no content is downloaded): a document plus
// its binary buffer, turned into .glb bytes or .gltf text. Used by test_gltf*.cpp.
#pragma once
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace gib::test {

struct GltfContent {
  nlohmann::json doc;
  std::vector<uint8_t> bin;

  // Appends `count` elements of `element` bytes as one bufferView + accessor; returns the accessor.
  int add(const void* data, size_t count, int component_type, const char* type, size_t element) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    const auto* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + count * element);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", count * element}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", component_type},
                                {"count", count}, {"type", type}});
    doc["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
    return static_cast<int>(doc["accessors"].size() - 1);
  }
};

inline constexpr int kFloat = 5126, kU16 = 5123, kU32 = 5125;

// One triangle (0,0,0) (1,0,0) (0,1,0) facing +Z, with normals, UVs and u16 indices, material
// "red", on node 0 of scene 0.
inline GltfContent triangle_content() {
  GltfContent g;
  g.doc = {{"asset", {{"version", "2.0"}}}};
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv[6] = {0, 0, 1, 0, 0, 1};
  const uint16_t idx[3] = {0, 1, 2};
  const int p = g.add(pos, 3, kFloat, "VEC3", 12);
  const int n = g.add(nrm, 3, kFloat, "VEC3", 12);
  const int t = g.add(uv, 3, kFloat, "VEC2", 8);
  const int i = g.add(idx, 3, kU16, "SCALAR", 2);
  g.doc["meshes"] = {{{"name", "tri"},
                      {"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}},
                                       {"indices", i}, {"material", 0}}}}}};
  g.doc["materials"] = {{{"name", "red"},
                         {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}}}};
  g.doc["nodes"] = {{{"name", "tri_node"}, {"mesh", 0}}};
  g.doc["scenes"] = {{{"nodes", {0}}}};
  g.doc["scene"] = 0;
  return g;
}

// A 2 x 2 24-bit BMP (14-byte file header, 40-byte info header, rows padded to 4 bytes):
// an image stb_image decodes, small enough to write by hand.
inline std::vector<uint8_t> tiny_bmp() {
  std::vector<uint8_t> b;
  auto u16 = [&](uint32_t v) { b.push_back(uint8_t(v)); b.push_back(uint8_t(v >> 8)); };
  auto u32 = [&](uint32_t v) { u16(v & 0xffff); u16(v >> 16); };
  b.push_back('B');
  b.push_back('M');
  u32(70); u32(0); u32(54);                      // file size, reserved, pixel offset
  u32(40); u32(2); u32(2); u16(1); u16(24);      // info header size, width, height, planes, bits
  u32(0); u32(16); u32(2835); u32(2835); u32(0); u32(0);
  for (int row = 0; row < 2; ++row) {
    for (int k = 0; k < 6; ++k) b.push_back(uint8_t(40 * (row + k)));
    b.push_back(0);
    b.push_back(0);
  }
  return b;
}

// Everything the import reads: a node tree (TRS and matrix), the triangle twice, a
// non-indexed quad without normals, BLEND / MASK / emissive-strength materials, the default
// material, a base colour texture (a BMP in a bufferView), point, spot and directional lights,
// a perspective camera. The fuzz test's seed.
inline GltfContent rich_content() {
  GltfContent g = triangle_content();
  const float quad[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
  const int q = g.add(quad, 6, kFloat, "VEC3", 12);
  g.doc["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", q}}}, {"material", 1}},
                                              {{"attributes", {{"POSITION", q}}}}}}});
  g.doc["materials"].push_back({{"name", "glass"}, {"alphaMode", "BLEND"},
                                {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 1, 0.25}}}}});
  g.doc["materials"].push_back({{"name", "lamp"}, {"emissiveFactor", {1, 0.5, 0.25}},
                                {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}});
  g.doc["materials"].push_back({{"name", "cutout"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.6},
                                {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.3}}}}});
  g.doc["meshes"][0]["primitives"][0]["material"] = 2;
  const std::vector<uint8_t> bmp = tiny_bmp();
  g.add(bmp.data(), bmp.size(), 5121, "SCALAR", 1);  // an accessor nobody uses, its view holds the image
  g.doc["images"] = {{{"bufferView", g.doc["bufferViews"].size() - 1}, {"mimeType", "image/bmp"}}};
  g.doc["textures"] = {{{"source", 0}}};
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  g.doc["extensionsUsed"] = nlohmann::json::array({"KHR_lights_punctual", "KHR_materials_emissive_strength"});
  g.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1, 0.5, 0}}, {"intensity", 10}, {"range", 7}},
      {{"type", "spot"}, {"intensity", 3}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 2}}};
  g.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 50}}}}};
  g.doc["nodes"] = {
      {{"name", "root"}, {"translation", {1, 0, 0}}, {"children", {1, 2}}},
      {{"name", "spun"}, {"rotation", {0, 0.70710678, 0, 0.70710678}}, {"scale", {2, 2, 2}}, {"mesh", 0}},
      {{"name", "moved"}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 3, 0, 1}}, {"mesh", 1}, {"children", {3}}},
      {{"name", "bulb"}, {"translation", {0, 2, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
      {{"name", "spot"}, {"rotation", {-0.70710678, 0, 0, 0.70710678}}, {"translation", {0, 4, 0}},
       {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
      {{"name", "sun"}, {"rotation", {-0.38268343, 0, 0, 0.92387953}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}},
      {{"name", "eye"}, {"translation", {0, 1, 5}}, {"camera", 0}},
      {{"name", "again"}, {"mesh", 0}}};
  g.doc["scenes"] = {{{"nodes", {0, 4, 5, 6, 7}}}};
  return g;
}

// The fuzz test mutates documents: only a first buffer that is an object gets its "uri" set.
inline bool has_buffer(const nlohmann::json& doc) {
  return doc.is_object() && doc.contains("buffers") && doc["buffers"].is_array() && !doc["buffers"].empty() &&
         doc["buffers"][0].is_object();
}

// .glb container: 12-byte header, JSON chunk (space padded), BIN chunk (zero padded).
inline std::vector<uint8_t> to_glb(const GltfContent& g) {
  nlohmann::json doc = g.doc;
  if (has_buffer(doc)) doc["buffers"][0].erase("uri");
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  std::vector<uint8_t> bin = g.bin;
  while (bin.size() % 4) bin.push_back(0);
  std::vector<uint8_t> out;
  auto u32 = [&](uint32_t v) { for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k))); };
  const uint32_t total = 12 + 8 + static_cast<uint32_t>(text.size()) + (bin.empty() ? 0 : 8 + static_cast<uint32_t>(bin.size()));
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(text.size()));
  u32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  if (!bin.empty()) {
    u32(static_cast<uint32_t>(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

inline std::string base64(const std::vector<uint8_t>& data) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    const size_t left = data.size() - i;
    const uint32_t v = uint32_t{data[i]} << 16 | (left > 1 ? uint32_t{data[i + 1]} << 8 : 0u) | (left > 2 ? data[i + 2] : 0u);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += left > 1 ? digits[(v >> 6) & 63] : '=';
    out += left > 2 ? digits[v & 63] : '=';
  }
  return out;
}

// .gltf text whose buffer is `uri` (a file name, or empty: the bin as a base64 data URI).
inline std::vector<uint8_t> to_gltf(const GltfContent& g, const std::string& uri = "") {
  nlohmann::json doc = g.doc;
  if (has_buffer(doc))
    doc["buffers"][0]["uri"] = uri.empty() ? "data:application/octet-stream;base64," + base64(g.bin) : uri;
  const std::string text = doc.dump(1);
  return {text.begin(), text.end()};
}

}  // namespace gib::test
