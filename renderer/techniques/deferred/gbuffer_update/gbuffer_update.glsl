// Body of gbuffer_update.comp (over the decal tile list: GIB_UPDATE_CLASSIFIED),
// gbuffer_update_vrcs[_plain].comp (the same with variable-rate shading: GIB_UPDATE_VRCS) and
// gbuffer_update_uber.comp (every pixel). Blends the scene's decals into the G-buffer albedo
// with decals.glsl, the code the gbuffer pass and the path tracer run; writes only the albedo's
// rgb, and only where some decal covers the pixel (the seed: "only write touched G-buffer
// channels"; sheen in its alpha is kept).
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update_shared.h"
#include "frame.glsl"
#include "renderer/techniques/deferred/include/tile_list.glsl"
#include "decals.glsl"

layout(local_size_x = kUpdateGroup, local_size_y = kUpdateGroup) in;
layout(set = 0, binding = kUpdateBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kUpdateBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kUpdateBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kUpdateBindAlbedo, rgba16f) uniform image2D gb_albedo;
#ifdef GIB_UPDATE_CLASSIFIED
layout(std430, set = 0, binding = kUpdateBindWorkloads) readonly buffer Workloads { uint wl[]; };
#endif
#ifdef GIB_UPDATE_VRCS
layout(std430, set = 0, binding = kUpdateBindRates) buffer Rates { uint vrcs_rate_words[]; };
#include "renderer/techniques/deferred/include/vrcs.glsl"
#endif
layout(push_constant) uniform Push { UpdatePush push; };

// Applies the decals' reduction kc to q's own albedo, where it changes anything.
void update_texel(ivec2 q, vec4 kc) {
  if (kc.w == 1.0) return;  // no decal covers it: the texel is not written
  vec4 a = imageLoad(gb_albedo, q);
  imageStore(gb_albedo, q, vec4(gib_decal_blend(a.rgb, kc), a.a));
}

void main() {
#ifdef GIB_UPDATE_CLASSIFIED
  ivec2 p = gib_tile_list_pixel(wl[kTileHeader + kTileListDecals * push.tiles + gib_tile_list_entry()], push.tiles_x);
#else
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
#endif
  ivec2 size = imageSize(gb_albedo);
  if (any(greaterThanEqual(p, size))) return;
  bool geometry = imageLoad(vbuffer, p).x != kVisibilityNone;
#ifdef GIB_UPDATE_VRCS
  // A pixel its coarse cell's anchor covers retires; the anchor evaluates the decals once at its
  // own position and normal and applies them to each covered pixel's own albedo.
  ivec2 cell;
  ivec2 anchor = gib_vrcs_anchor(p, gib_vrcs_rate(p, push.rate_tiles_x), cell);
  if (gib_vrcs_follows(p, anchor, size)) return;
#endif
  if (!geometry) return;
  vec4 kc = gib_decals_at(imageLoad(gb_position, p).xyz, imageLoad(gb_normal, p).xyz);
  update_texel(p, kc);
#ifdef GIB_UPDATE_VRCS
  uint covered = 0u;
  for (int y = 0; y < cell.y; ++y)
    for (int x = 0; x < cell.x; ++x) {
      ivec2 q = anchor + ivec2(x, y);
      if (!gib_vrcs_follows(q, anchor, size)) continue;
      update_texel(q, kc);
      ++covered;
    }
  gib_vrcs_count(kVrcsStats + kVrcsStatDecaled, 1u, 1u + covered);  // kVrcsStatDecaledOf follows
#endif
}
