// Body of material_classify's count kernels: per (tile, material), the geometry pixels it has.
// material_classify_count.comp adds each pixel with its own atomic; material_classify_count_
// subgroup.comp (GIB_COUNT_SUBGROUPS, devices with subgroup ballot) adds once per distinct
// (tile, material) in a subgroup, the count of its lanes: an 8x8 workgroup lies in one 32x32
// tile, so a subgroup mostly holds one or two materials, and the contended atomics on the same
// word fall by about the subgroup size. Integer sums: the counts are the same either way.
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)

layout(local_size_x = kMatClassifyGroup, local_size_y = kMatClassifyGroup) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(vbuffer)))) return;
  uvec2 ids = imageLoad(vbuffer, p).xy;
  if (ids.x == kVisibilityNone) return;
  uint tile = uint(p.x >> kDeferredTileShift) + uint(p.y >> kDeferredTileShift) * push.tiles_x;
  uint word = kSegHeader + tile * push.materials + gib_instances[ids.y].material;
#ifdef GIB_COUNT_SUBGROUPS
  // Each pass takes the first active lane's word; the lanes holding it add their count with one
  // atomic and leave, the others go round again.
  for (;;) {
    uint first = subgroupBroadcastFirst(word);
    uvec4 same = subgroupBallot(word == first);
    if (word == first) {
      if (subgroupElect()) atomicAdd(seg[first], subgroupBallotBitCount(same));
      break;
    }
  }
#else
  atomicAdd(seg[word], 1u);
#endif
}
