#version 460
#extension GL_GOOGLE_include_directive : require
// Scan, step 2 of 3, one workgroup: the blocks' sums in the order shader, block give each
// block's first slot, each shader's first wave and its indirect dispatch args, and the
// statistics. Blocks per shader: ceil(T M / kMatScanSize), 225 at 2560x1440 (3600 tiles) with
// 16 materials: one iteration of the loop below.
#include "renderer/techniques/deferred/material_classify/material_classify_scan_common.glsl"

void main() {
  uint slot = 0u, pixels = 0u, segments = 0u;
  for (uint s = 0u; s < kDeferredShaderCount; ++s) {
    uint first = slot;
    for (uint base = 0u; base < push.blocks; base += kMatScanSize) {
      uint b = base + gl_LocalInvocationIndex;
      bool in_range = b < push.blocks;
      uint padded = in_range ? blk[block_word(s, b) + 0u] : 0u;
      uint count = in_range ? blk[block_word(s, b) + 1u] : 0u;
      uint nonempty = in_range ? blk[block_word(s, b) + 2u] : 0u;
      uvec3 total;
      uint before = gib_workgroup_exclusive_scan3(uvec3(padded, count, nonempty), total).x;
      if (in_range) blk[block_word(s, b) + 3u] = slot + before;
      slot += total.x;
      pixels += total.y;
      segments += total.z;
    }
    if (gl_LocalInvocationIndex == 0u) {
      seg[4u * s + 0u] = (slot - first) / kDeferredWave;
      seg[4u * s + 1u] = 1u;
      seg[4u * s + 2u] = 1u;
      seg[4u * s + 3u] = first / kDeferredWave;
    }
  }
  if (gl_LocalInvocationIndex == 0u) {
    seg[kSegStats + kStatPixels] = pixels;
    seg[kSegStats + kStatWaves] = slot / kDeferredWave;
    seg[kSegStats + kStatPaddingSlots] = slot - pixels;
    seg[kSegStats + kStatSegments] = segments;
  }
}
