#version 460
#extension GL_GOOGLE_include_directive : require
// Stability scan of an r32_uint image (a storage image load: cheaper than a sampler on a CPU
// device): RGB9E5 words decoded to 3 channels (encoding rgb9e5), else float bits. See
// stability_scan.glsl.
#define STABILITY_SCAN_IMAGE
#include "renderer/graph/stability_scan.glsl"

layout(set = 0, binding = kStabilityScanBindSource, r32ui) uniform readonly uimage2D source;

void scan_element(uint x, uint y) {
  uvec4 w = imageLoad(source, ivec2(x, y));
  if (pc.encoding == kStabilityEncodingRgb9e5) {
    vec3 c = gib_unpack_rgb9e5(w.x);
    scan_value(c.r, 0u);
    scan_value(c.g, 1u);
    scan_value(c.b, 2u);
  } else {
    scan_value(uintBitsToFloat(w.x), 0u);
  }
}
