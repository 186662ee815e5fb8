#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/visibility/visibility_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)

layout(location = 0) flat out uint out_triangle;
layout(location = 1) flat out uint out_instance;
layout(location = 2) out vec2 out_uv;

// Non-indexed draw of 3 vertices per triangle: the vertex index names the triangle and corner.
void main() {
  uint tri = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  GpuTriangle t = gib_triangles[tri];
  uint vi = corner == 0u ? t.i0 : (corner == 1u ? t.i1 : t.i2);
  GpuVertex v = gib_vertices[vi];
  out_triangle = tri;
  out_instance = t.instance;
  out_uv = vec2(v.u, v.v);
  gl_Position = gib_frame.view_proj * vec4(v.position, 1.0);
}
