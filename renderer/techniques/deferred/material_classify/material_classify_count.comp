#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)

// Pixels per (tile, material): one workgroup per tile counts its 1024 pixels in group-shared
// counters and stores them, instead of one global atomic per pixel; materials past
// kMatCountShared (scenes with that many) count with global atomics. Integer counts: the same
// words in any order.
layout(local_size_x = kMatScanSize) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

const uint kPerInvocation = kDeferredTile * kDeferredTile / kMatScanSize;
shared uint s_count[kMatCountShared];

void main() {
  uint tile = gl_WorkGroupID.x;
  for (uint m = gl_LocalInvocationIndex; m < kMatCountShared; m += kMatScanSize) s_count[m] = 0u;
  barrier();
  ivec2 origin = ivec2(tile % push.tiles_x, tile / push.tiles_x) * int(kDeferredTile);
  ivec2 size = imageSize(vbuffer);
  for (uint k = 0u; k < kPerInvocation; ++k) {
    uint i = gl_LocalInvocationIndex * kPerInvocation + k;
    ivec2 p = origin + ivec2(i % kDeferredTile, i / kDeferredTile);
    if (!all(lessThan(p, size))) continue;
    uvec2 ids = imageLoad(vbuffer, p).xy;
    if (ids.x == kVisibilityNone) continue;
    uint material = gib_instances[ids.y].material;
    if (material < kMatCountShared)
      atomicAdd(s_count[material], 1u);
    else
      atomicAdd(seg[kSegHeader + tile * push.materials + material], 1u);
  }
  barrier();
  for (uint m = gl_LocalInvocationIndex; m < min(push.materials, kMatCountShared); m += kMatScanSize)
    seg[kSegHeader + tile * push.materials + m] = s_count[m];
}
