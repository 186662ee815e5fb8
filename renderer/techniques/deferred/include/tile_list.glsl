// Dispatches over a tile list of `tile_workloads` (tile_classify): kLightingGroupsPerTile 8x8
// workgroups cover one listed 32x32 tile. Needs deferred_shared.h.
#ifndef GIB_DEFERRED_TILE_LIST_GLSL
#define GIB_DEFERRED_TILE_LIST_GLSL

// The entry of the list this workgroup works on.
uint gib_tile_list_entry() { return gl_WorkGroupID.x / kLightingGroupsPerTile; }

// This invocation's pixel in listed tile `tile` (an index into the tiles_x-wide tile grid).
ivec2 gib_tile_list_pixel(uint tile, uint tiles_x) {
  uint part = gl_WorkGroupID.x % kLightingGroupsPerTile;
  return ivec2(tile % tiles_x, tile / tiles_x) * int(kDeferredTile) + ivec2(part % 4u, part / 4u) * int(kLightingGroup) +
         ivec2(gl_LocalInvocationID.xy);
}

#endif
