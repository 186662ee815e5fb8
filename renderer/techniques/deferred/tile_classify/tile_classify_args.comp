#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/tile_classify/tile_classify_shared.h"
#define GIB_SCAN_SIZE kTileScanSize
#include "renderer/techniques/deferred/include/deferred_scan.glsl"

layout(local_size_x = kTileScanSize) in;
layout(set = 0, binding = kTileBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kTileBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(std430, set = 0, binding = kTileBindWorkloads) buffer Workloads { uint wl[]; };
layout(push_constant) uniform Push { TilePush push; };

// The lighting workload of a tile: the cheapest permutation with every feature it has.
uint workload_of(uint mask) {
  if ((mask & kTileFeatureTranslucent) != 0u) return kWorkloadTranslucent;
  if ((mask & kTileFeatureCloth) != 0u) return kWorkloadCloth;
  if ((mask & kTileFeatureOpaque) != 0u) return kWorkloadOpaque;
  return kWorkloadSky;
}

bool in_list(uint list, uint mask) {
  return list == kTileListDecals ? (mask & kTileFeatureDecals) != 0u : workload_of(mask) == list;
}

void main() {
  uint masks = kTileHeader + kTileListCount * push.tiles;
  for (uint w = 0u; w < kTileListCount; ++w) {
    uint count = 0u;
    for (uint base = 0u; base < push.tiles; base += kTileScanSize) {
      uint t = base + gl_LocalInvocationIndex;
      bool mine = t < push.tiles && in_list(w, wl[masks + t]);
      uint total;
      uint before = gib_workgroup_exclusive_scan(mine ? 1u : 0u, total);
      if (mine) wl[kTileHeader + w * push.tiles + count + before] = t;
      count += total;
    }
    if (gl_LocalInvocationIndex == 0u) {
      if (w == 0u) wl[kTileStats + kTileStatTiles] = push.tiles;
      wl[4u * w + 0u] = count * kLightingGroupsPerTile;
      wl[4u * w + 1u] = 1u;
      wl[4u * w + 2u] = 1u;
      wl[4u * w + 3u] = count;
    }
  }
}
