// Image content written by the texture tests themselves: uncompressed 32-bit TGA files (a format
// stb_image decodes, simple enough to write by hand) and a glTF quad whose material uses one as
// its base colour texture. Used by tests/test_textures*.cpp.
#pragma once
#include <cstdint>
#include <vector>

#include "tests/gltf_test_content.h"

namespace gib::test {

// RGBA8 pixels (rows top to bottom) as an uncompressed true-colour TGA with a top-left origin.
inline std::vector<uint8_t> tga(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
  std::vector<uint8_t> b(18, 0);
  b[2] = 2;  // uncompressed true colour
  b[12] = uint8_t(width);
  b[13] = uint8_t(width >> 8);
  b[14] = uint8_t(height);
  b[15] = uint8_t(height >> 8);
  b[16] = 32;    // bits per pixel
  b[17] = 0x28;  // 8 alpha bits, top-left origin
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
    b.push_back(rgba[i + 2]);  // BGRA
    b.push_back(rgba[i + 1]);
    b.push_back(rgba[i]);
    b.push_back(rgba[i + 3]);
  }
  return b;
}

// A quad over (0,0,0)..(1,1,0) facing +Z, uv = (x, 1 - y) (glTF's top-left origin), whose
// material "leaves" is MASK (cutoff 0.5) with `image` (TGA bytes, in a bufferView) as its base
// colour texture.
inline GltfContent textured_quad_content(const std::vector<uint8_t>& image) {
  GltfContent g;
  g.doc = {{"asset", {{"version", "2.0"}}}};
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const int p = g.add(pos, 4, kFloat, "VEC3", 12);
  const int n = g.add(nrm, 4, kFloat, "VEC3", 12);
  const int t = g.add(uv, 4, kFloat, "VEC2", 8);
  const int i = g.add(idx, 6, kU16, "SCALAR", 2);
  g.add(image.data(), image.size(), 5121, "SCALAR", 1);  // the image's view (an unused accessor)
  g.doc["images"] = {{{"bufferView", g.doc["bufferViews"].size() - 1}, {"mimeType", "image/x-tga"}}};
  g.doc["textures"] = {{{"source", 0}}};
  g.doc["meshes"] = {{{"name", "quad"},
                      {"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}},
                                       {"indices", i}, {"material", 0}}}}}};
  g.doc["materials"] = {{{"name", "leaves"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.5},
                         {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"baseColorTexture", {{"index", 0}}}}}}};
  g.doc["nodes"] = {{{"name", "quad_node"}, {"mesh", 0}}};
  g.doc["scenes"] = {{{"nodes", {0}}}};
  g.doc["scene"] = 0;
  return g;
}

}  // namespace gib::test
