// Shared by tests/gow_cubemap_test.comp and tests/test_gow_reflections.cpp: gow_cubemap.glsl
// (the reflection cube map's addressing and box projection) on the device, for a comparison
// with the CPU mirror (renderer/techniques/gow_ragnarok/gow_cubemap.h).
#ifndef GOW_CUBEMAP_TEST_SHARED_H
#define GOW_CUBEMAP_TEST_SHARED_H
#ifdef __cplusplus
#include <cstdint>
namespace gib::gow_cubemap_test {
using uint = uint32_t;
#endif

#define GOW_CUBEMAP_TEST_BINDING_QUERIES 0
#define GOW_CUBEMAP_TEST_BINDING_OUT 1
#define GOW_CUBEMAP_TEST_WORKGROUP_SIZE 64
#define GOW_CUBEMAP_TEST_QUERY_FLOATS 16
#define GOW_CUBEMAP_TEST_OUT_WORDS 8

struct GowCubemapTestQuery {  // 16 floats, read as words
  float x[3], d[3], bmin[3], bmax[3], capture[3];
  float size;  // N (an integer)
};

struct GowCubemapTestOut {  // 8 words
  int texel[2];      // gow_cube_texel(d, N)
  float project[3];  // gow_box_project(x, d, bmin, bmax, capture)
  float exit;        // gow_box_exit(x, d, bmin, bmax)
  int pad[2];
};

struct GowCubemapTestPush {
  uint count;
};

#ifdef __cplusplus
}  // namespace gib::gow_cubemap_test
#endif
#endif
