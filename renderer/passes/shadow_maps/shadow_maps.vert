#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/shadow_maps/shadow_maps_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "shadow_cascades.glsl"
layout(push_constant) uniform Push { ShadowCascadePush push; };

layout(location = 0) flat out uint out_instance;
layout(location = 1) out vec2 out_uv;

// One cascade (push.counts.z) per draw, into its square of the atlas (the viewport).
void main() {
  uint tri = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  GpuTriangle t = gib_triangles[tri];
  GpuVertex v = gib_vertices[corner == 0u ? t.i0 : (corner == 1u ? t.i1 : t.i2)];
  out_instance = t.instance;
  out_uv = vec2(v.u, v.v);
  vec3 cam, fwd;
  float tan_y, aspect;
  csm_camera(cam, fwd, tan_y, aspect);
  ShadowBasis b = csm_shadow_basis(gib_frame.sun_dir.xyz);
  ShadowCascade c = csm_cascade(push.counts.z, cam, fwd, tan_y, aspect, b, push);
  vec3 q = csm_shadow_project(c, b, v.position - cam);
  gl_Position = vec4(q.xy * 2.0 - 1.0, q.z, 1.0);
}
