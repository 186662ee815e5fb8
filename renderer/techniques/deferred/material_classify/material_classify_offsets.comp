#version 460
#extension GL_GOOGLE_include_directive : require
// Scan, step 3 of 3: one workgroup per block writes each non-empty segment's first slot, its
// block's first slot plus the padded sizes before it in the block (same shader).
#include "renderer/techniques/deferred/material_classify/material_classify_scan_common.glsl"

void main() {
  uint b = gl_WorkGroupID.x;
  uint e = b * kMatScanSize + gl_LocalInvocationIndex;
  uint offsets = kSegHeader + push.tiles * push.materials;
  for (uint s = 0u; s < kDeferredShaderCount; ++s) {
    uint count = entry_count(e, s);
    uint total;
    uint before = gib_workgroup_exclusive_scan(padded_size(count), total);
    if (count > 0u) seg[offsets + e] = blk[block_word(s, b) + 3u] + before;
  }
}
