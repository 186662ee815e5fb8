// Body of tile_classify_mask.comp (GIB_TILE_BALLOT: the seed's scalarised atomics) and
// tile_classify_mask_plain.comp (one atomicOr per pixel).
#include "renderer/techniques/deferred/tile_classify/tile_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "decals.glsl"

layout(local_size_x = kTileMaskGroup, local_size_y = kTileMaskGroup) in;
layout(set = 0, binding = kTileBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kTileBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kTileBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kTileBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(std430, set = 0, binding = kTileBindWorkloads) buffer Workloads { uint wl[]; };
layout(push_constant) uniform Push { TilePush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(p, imageSize(gb_position)));
  uint features = 0u;
  uint tile = 0u;
  if (inside) {
    tile = uint(p.x >> kDeferredTileShift) + uint(p.y >> kDeferredTileShift) * push.tiles_x;
    vec4 pos = imageLoad(gb_position, p);
    vec4 em = imageLoad(gb_emissive, p);
    if (pos.w == 0.0) {
      features = kTileFeatureSky;
    } else {
      features = em.w > 0.0 ? kTileFeatureTranslucent : kTileFeatureOpaque;
      if (any(greaterThan(em.rgb, vec3(0.0)))) features |= kTileFeatureEmissive;
      // The material's BRDF class (the G-buffer albedo is gbuffer_update's to modify after this).
      uvec2 ids = imageLoad(vbuffer, p).xy;
      if (ids.x != kVisibilityNone && gib_materials[gib_instances[ids.y].material].sheen > 0.0)
        features |= kTileFeatureCloth;
      // A pixel some decal covers: the same test gbuffer_update's blend makes.
      if (gib_decal_count() > 0u && gib_decals_at(pos.xyz, imageLoad(gb_normal, p).xyz).w < 1.0)
        features |= kTileFeatureDecals;
    }
  }
  uint index = kTileHeader + kTileListCount * push.tiles + tile;
#ifdef GIB_TILE_BALLOT
  // One lane per distinct tile in the subgroup ORs the subgroup's features for that tile: the
  // first pending lane's tile is broadcast, every lane of that tile is served at once.
  bool pending = inside;
  while (subgroupAny(pending)) {
    if (pending) {
      uint first_tile = subgroupBroadcastFirst(tile);
      bool same = tile == first_tile;
      uint merged = subgroupOr(same ? features : 0u);
      if (subgroupElect()) atomicOr(wl[index], merged);  // the elected lane is the first: its tile
      if (same) pending = false;
    }
  }
#else
  if (inside) atomicOr(wl[index], features);
#endif
}
