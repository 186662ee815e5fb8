#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/tile_classify/tile_classify_shared.h"
#define GIB_SCAN_SIZE kTileScanSize
#define GIB_SCAN_UVEC2
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

// A tile's membership of the five lists as 10-bit counters: lists 0-2 (workloads sky, opaque,
// cloth) in x, list 3 (translucent) and list 4 (decals) in y. One scan of the pair ranks a chunk
// of tiles in every list at once; a chunk adds at most kTileScanSize (256) to a counter, so the
// fields never carry into each other.
const uint kListBits = 10u;
uvec2 membership(uint mask) {
  uint w = workload_of(mask);
  uvec2 m = w < 3u ? uvec2(1u << (kListBits * w), 0u) : uvec2(0u, 1u);
  if (in_list(kTileListDecals, mask)) m.y |= 1u << kListBits;
  return m;
}
uint list_field(uvec2 v, uint list) {
  return (list < 3u ? v.x >> (kListBits * list) : v.y >> (kListBits * (list - 3u))) & ((1u << kListBits) - 1u);
}

// Each list holds its tiles in increasing order, as a scan per list would write them.
void main() {
  uint masks = kTileHeader + kTileListCount * push.tiles;
  uint count[kTileListCount];
  for (uint w = 0u; w < kTileListCount; ++w) count[w] = 0u;
  for (uint base = 0u; base < push.tiles; base += kTileScanSize) {
    uint t = base + gl_LocalInvocationIndex;
    uvec2 mine = t < push.tiles ? membership(wl[masks + t]) : uvec2(0u);
    uvec2 total;
    uvec2 before = gib_workgroup_exclusive_scan2(mine, total);
    for (uint w = 0u; w < kTileListCount; ++w) {
      if (list_field(mine, w) != 0u) wl[kTileHeader + w * push.tiles + count[w] + list_field(before, w)] = t;
      count[w] += list_field(total, w);
    }
  }
  if (gl_LocalInvocationIndex == 0u) {
    wl[kTileStats + kTileStatTiles] = push.tiles;
    for (uint w = 0u; w < kTileListCount; ++w) {
      wl[4u * w + 0u] = count[w] * kLightingGroupsPerTile;
      wl[4u * w + 1u] = 1u;
      wl[4u * w + 2u] = 1u;
      wl[4u * w + 3u] = count[w];
    }
  }
}
