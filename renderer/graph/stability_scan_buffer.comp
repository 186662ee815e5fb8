#version 460
#extension GL_GOOGLE_include_directive : require
// Stability scan of a buffer's value words: element i's values are words
// [i * stride + first, i * stride + first + words), floats or RGB9E5 (channels 3k..3k+2).
// See stability_scan.glsl.
#include "renderer/graph/stability_scan.glsl"

layout(std430, set = 0, binding = kStabilityScanBindSource) readonly buffer Source { uint words[]; };

void scan_element(uint i) {
  const uint base = i * pc.stride_words + pc.first_word;
  for (uint k = 0u; k < pc.words; ++k) {
    uint w = words[base + k];
    if (pc.encoding == kStabilityEncodingRgb9e5) {
      vec3 c = gib_unpack_rgb9e5(w);
      scan_value(c.r, 3u * k);
      scan_value(c.g, 3u * k + 1u);
      scan_value(c.b, 3u * k + 2u);
    } else {
      scan_value(uintBitsToFloat(w), k);
    }
  }
}
