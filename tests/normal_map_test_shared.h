// Shared by tests/normal_map_test.comp and tests/test_normal_map.cpp: normal_map.glsl's
// gib_normal_map on the device, for a comparison with the CPU mirror (renderer/scene/normal_map.h).
#ifndef NORMAL_MAP_TEST_SHARED_H
#define NORMAL_MAP_TEST_SHARED_H
#ifdef __cplusplus
#include <cstdint>
namespace gib::normal_map_test {
using uint = uint32_t;
#endif

#define NORMAL_MAP_TEST_BINDING_QUERIES 0
#define NORMAL_MAP_TEST_BINDING_OUT 1
#define NORMAL_MAP_TEST_WORKGROUP_SIZE 64

struct NormalMapTestQuery {  // 88 bytes: 22 floats
  float n[3];
  float scale;
  float p[9];      // three positions
  float t[6];      // three uvs
  float texel[3];
};

struct NormalMapTestOut {  // 16 bytes
  float n[3];
  float pad;
};

struct NormalMapTestPush {
  uint count;
};

#ifdef __cplusplus
}  // namespace gib::normal_map_test
#endif
#endif
