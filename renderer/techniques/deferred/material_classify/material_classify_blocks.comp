#version 460
#extension GL_GOOGLE_include_directive : require
// Scan, step 1 of 3: one workgroup per block of kMatScanSize entries sums, per shader, the
// block's padded slots, pixels and non-empty segments.
#include "renderer/techniques/deferred/material_classify/material_classify_scan_common.glsl"

void main() {
  uint b = gl_WorkGroupID.x;
  uint e = b * kMatScanSize + gl_LocalInvocationIndex;
  for (uint s = 0u; s < kDeferredShaderCount; ++s) {
    uint count = entry_count(e, s);
    uvec3 total;  // padded slots, pixels, non-empty segments
    gib_workgroup_exclusive_scan3(uvec3(padded_size(count), count, count > 0u ? 1u : 0u), total);
    if (gl_LocalInvocationIndex == 0u) {
      blk[block_word(s, b) + 0u] = total.x;
      blk[block_word(s, b) + 1u] = total.y;
      blk[block_word(s, b) + 2u] = total.z;
    }
  }
}
