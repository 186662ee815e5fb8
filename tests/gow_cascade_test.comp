// gow-ragnarok's cascade selection and seam blend weight (shadow_cascades.glsl) on test points, for
// comparison with the CPU mirror (shadow_cascades.h) in tests/test_gow_shadows.cpp.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "tests/gow_cascade_test_shared.h"
#include "frame.glsl"
#include "shadow_cascades.glsl"
layout(push_constant) uniform Push { GowCascadeTestPush push; };
layout(std430, set = 0, binding = kGowCascadeTestBindIn) readonly buffer InBuffer { GowCascadeTestIn items[]; };
layout(std430, set = 0, binding = kGowCascadeTestBindOut) writeonly buffer OutBuffer { GowCascadeTestOut results[]; };
layout(local_size_x = kGowCascadeTestGroup) in;

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= uint(items.length())) return;
  GowCascadeTestIn t = items[k];
  ShadowBasis b = csm_shadow_basis(push.sun.xyz);
  vec3 cam = push.camera.xyz, fwd = push.forward.xyz;
  float tan_y = push.camera.w, aspect = push.forward.w;
  float margin_texels = 2.0 + push.cascades.area.w;
  uint i = csm_select_cascade(cam, fwd, tan_y, aspect, b, push.cascades, t.x_rel.xyz, t.x_rel.w, margin_texels);
  float w = i < kShadowMaxCascades
                ? csm_cascade_blend(cam, fwd, tan_y, aspect, b, push.cascades, i, t.x_rel.xyz, t.x_rel.w, margin_texels)
                : 0.0;
  results[k].result = vec4(float(i), w, 0.0, 0.0);
}
