// Shared by tests/textures_test.comp and tests/test_textures_gpu.cpp: the GPU texture fetch and
// filter (renderer/shaders/include/textures.glsl) run on queries, for a bit-for-bit comparison
// with the CPU mirror (renderer/scene/texture.h).
#ifndef TEXTURES_TEST_SHARED_H
#define TEXTURES_TEST_SHARED_H
#ifdef __cplusplus
#include <cstdint>
namespace gib::textures_test {
using uint = uint32_t;
#endif

#define TEXTURES_TEST_BINDING_TEXTURES 0
#define TEXTURES_TEST_BINDING_QUERIES 1
#define TEXTURES_TEST_BINDING_OUT 2
#define TEXTURES_TEST_WORKGROUP_SIZE 64

struct TexturesTestQuery {  // 32 bytes
  uint texture;
  uint level;      // for the bilinear sample
  float u, v;
  float dudx, dvdx;  // footprint: uv derivatives along x and y
  float dudy, dvdy;
};

struct TexturesTestOut {  // 48 bytes, floats as bits
  uint bilinear[4];  // gib_texture_bilinear(texture, level, uv)
  uint sampled[4];   // gib_texture_sample(texture, uv, footprint)
  uint level;        // gib_texture_level(texture, footprint)
  uint pad[3];
};

struct TexturesTestPush {
  uint count;
};

#ifdef __cplusplus
}  // namespace gib::textures_test
#endif
#endif
