#version 460
#extension GL_GOOGLE_include_directive : require
// Stability scan of a float image (any float format, read through a sampler, so formats a
// shader cannot store, E5B9G9R9 and depth, work too). See stability_scan.glsl.
#define STABILITY_SCAN_IMAGE
#include "renderer/graph/stability_scan.glsl"

layout(set = 0, binding = kStabilityScanBindSource) uniform sampler2D source;

void scan_element(uint x, uint y) {
  vec4 v = texelFetch(source, ivec2(x, y), 0);
  scan_value(v.x, 0u);
  scan_value(v.y, 1u);
  scan_value(v.z, 2u);
  scan_value(v.w, 3u);
}
