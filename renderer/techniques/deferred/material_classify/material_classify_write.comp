#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#define GIB_SCAN_SIZE kMatScanSize
#include "renderer/techniques/deferred/include/deferred_scan.glsl"

// One workgroup per tile; invocation i owns the tile's pixels 4i .. 4i + 3 in raster order.
// For each material present in the tile, a prefix sum ranks its pixels in raster order; the
// workgroup pads its lists and a share of the buffer's unused tail with kDeferredPixelPad.
layout(local_size_x = kMatScanSize) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(std430, set = 0, binding = kMatBindCommands) writeonly buffer Commands { uint commands[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

const uint kPerInvocation = kDeferredTile * kDeferredTile / kMatScanSize;

void main() {
  uint tile = gl_WorkGroupID.x;
  ivec2 origin = ivec2(tile % push.tiles_x, tile / push.tiles_x) * int(kDeferredTile);
  ivec2 size = imageSize(vbuffer);
  uint mats[kPerInvocation];
  uint local[kPerInvocation];
  for (uint k = 0u; k < kPerInvocation; ++k) {
    uint i = gl_LocalInvocationIndex * kPerInvocation + k;
    local[k] = i;
    ivec2 p = origin + ivec2(i % kDeferredTile, i / kDeferredTile);
    mats[k] = 0xffffffffu;
    if (all(lessThan(p, size))) {
      uvec2 ids = imageLoad(vbuffer, p).xy;
      if (ids.x != kVisibilityNone) mats[k] = gib_instances[ids.y].material;
    }
  }
  uint entries = push.tiles * push.materials;
  for (uint m = 0u; m < push.materials; ++m) {
    uint e = tile * push.materials + m;
    if (seg[kSegHeader + e] == 0u) continue;  // uniform: the same word for the whole workgroup
    uint mine = 0u;
    for (uint k = 0u; k < kPerInvocation; ++k) mine += mats[k] == m ? 1u : 0u;
    uint total;
    uint rank = gib_workgroup_exclusive_scan(mine, total);
    uint first = seg[kSegHeader + entries + e];
    for (uint k = 0u; k < kPerInvocation; ++k) {
      if (mats[k] != m) continue;
      uint i = local[k];
      commands[first + rank] = tile << 10u | (i / kDeferredTile) << 5u | (i % kDeferredTile);
      ++rank;
    }
    // The list's padding up to its next multiple of kDeferredWave entries.
    uint padded = (total + kDeferredWave - 1u) / kDeferredWave * kDeferredWave;
    for (uint j = total + gl_LocalInvocationIndex; j < padded; j += kMatScanSize) commands[first + j] = kDeferredPixelPad;
  }
  // The entries past the last list (the buffer is sized for every segment non-empty), shared by
  // all workgroups: every word of pixel_commands is written each frame, without a fill before
  // the pass (a 20 MB transfer and its barrier at 2560x1440).
  uint used = seg[kSegStats + kStatWaves] * kDeferredWave;
  for (uint j = used + tile * kMatScanSize + gl_LocalInvocationIndex; j < uint(commands.length()); j += push.tiles * kMatScanSize)
    commands[j] = kDeferredPixelPad;
}
