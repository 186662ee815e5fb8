#version 460
// Raster fill-rate calibration (perf/calibration.cpp): `layers` full-screen triangles, each
// nearer than the last, so every fragment of every layer passes the depth test and writes the
// colour and depth targets: the fill work of a visibility pass (D32 depth test and write, one
// rg32_uint target) with no scene, no vertex fetch and no fragment arithmetic.
#extension GL_GOOGLE_include_directive : require
#include "perf/calibration_shared.h"
layout(push_constant) uniform Push { CalibRasterPush push; };
layout(location = 0) flat out uint out_layer;

void main() {
  uint layer = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  // One triangle covering the viewport: (-1,-1), (3,-1), (-1,3).
  vec2 p = vec2(corner == 1u ? 3.0 : -1.0, corner == 2u ? 3.0 : -1.0);
  float z = 1.0 - float(layer + 1u) / float(push.layers + 1u);
  out_layer = layer;
  gl_Position = vec4(p, z, 1.0);
}
