#version 450
// GPU side of tests/test_glossy_brdf.cpp: brdf.glsl's glossy class on the device, compared with
// the CPU mirror (renderer/scene/material_eval.h).
#extension GL_GOOGLE_include_directive : require

#include "tests/glossy_brdf_test_shared.h"

layout(std430, binding = GLOSSY_BRDF_TEST_BINDING_QUERIES) readonly buffer Queries { float qw[]; };
layout(std430, binding = GLOSSY_BRDF_TEST_BINDING_OUT) writeonly buffer Out { float ow[]; };
layout(push_constant) uniform Push { GlossyBrdfTestPush pc; };
layout(local_size_x = GLOSSY_BRDF_TEST_WORKGROUP_SIZE) in;

#include "sampling.glsl"
#include "brdf.glsl"

vec3 q3(uint b) { return vec3(qw[b], qw[b + 1u], qw[b + 2u]); }
void o3(uint b, vec3 v) {
  ow[b] = v.x;
  ow[b + 1u] = v.y;
  ow[b + 2u] = v.z;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  uint b = i * GLOSSY_BRDF_TEST_QUERY_FLOATS;
  vec3 n = q3(b), wo = q3(b + 3u), wi = q3(b + 6u), albedo = q3(b + 9u);
  float roughness = qw[b + 12u], metalness = qw[b + 13u];
  vec2 u = vec2(qw[b + 14u], qw[b + 15u]);
  float pick = qw[b + 16u];
  vec3 spec, diffuse;
  gib_glossy_eval(n, wo, wi, albedo, roughness, metalness, spec, diffuse);
  float p_spec = gib_glossy_spec_probability(n, wo, albedo, metalness);
  uint o = i * GLOSSY_BRDF_TEST_OUT_FLOATS;
  o3(o, spec);
  o3(o + 3u, diffuse);
  ow[o + 6u] = p_spec;
  ow[o + 7u] = gib_glossy_pdf(n, wo, wi, roughness, p_spec);
  o3(o + 8u, gib_glossy_sample(n, wo, roughness, p_spec, u, pick));
  o3(o + 11u, gib_ggx_sample_vndf(n, wo, gib_ggx_alpha(roughness), u));
}
