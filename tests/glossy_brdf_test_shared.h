// Shared by tests/glossy_brdf_test.comp and tests/test_glossy_brdf.cpp: brdf.glsl's glossy class
// on the device, for a comparison with the CPU mirror (renderer/scene/material_eval.h).
#ifndef GLOSSY_BRDF_TEST_SHARED_H
#define GLOSSY_BRDF_TEST_SHARED_H
#ifdef __cplusplus
#include <cstdint>
namespace gib::glossy_brdf_test {
using uint = uint32_t;
#endif

#define GLOSSY_BRDF_TEST_BINDING_QUERIES 0
#define GLOSSY_BRDF_TEST_BINDING_OUT 1
#define GLOSSY_BRDF_TEST_WORKGROUP_SIZE 64
#define GLOSSY_BRDF_TEST_QUERY_FLOATS 18
#define GLOSSY_BRDF_TEST_OUT_FLOATS 14

struct GlossyBrdfTestQuery {  // 18 floats, read as words
  float n[3], wo[3], wi[3], albedo[3];
  float roughness, metalness;
  float u0, u1, pick;
  float pad;
};

struct GlossyBrdfTestOut {  // 14 floats, written as words
  float spec[3], diffuse[3];
  float p_spec, pdf;
  float sampled[3];  // gib_glossy_sample(n, wo, roughness, p_spec, u, pick)
  float vndf[3];     // gib_ggx_sample_vndf(n, wo, alpha, u)
};

struct GlossyBrdfTestPush {
  uint count;
};

#ifdef __cplusplus
}  // namespace gib::glossy_brdf_test
#endif
#endif
