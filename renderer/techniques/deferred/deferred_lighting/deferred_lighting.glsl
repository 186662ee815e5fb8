// Body of deferred_lighting.comp (one workload over its tile list: GIB_LIGHTING_CLASSIFIED),
// deferred_lighting_vrcs.comp (the same with variable-rate shading: GIB_LIGHTING_VRCS) and
// deferred_lighting_uber.comp (every pixel, every feature). Both shade with gib_direct_light(),
// the code direct_lighting runs; a workload compiled without a feature gives the same value
// wherever the feature is absent, so the two agree bit for bit.
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting_shared.h"
#include "frame.glsl"
#include "renderer/techniques/deferred/include/tile_list.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
layout(constant_id = kLightSpecSun) const bool kHasSun = true;
layout(constant_id = kLightSpecSky) const bool kHasSky = true;
layout(constant_id = kLightSpecLocal) const bool kHasLocal = true;
layout(constant_id = kLightSpecEmissive) const bool kHasEmissive = true;
layout(constant_id = kLightSpecWorkload) const uint kWorkload = kWorkloadTranslucent;
layout(constant_id = kLightSpecSkyUnoccluded) const bool kSkyUnoccluded = false;
#define GIB_ALPHA_SPEC kLightSpecAlpha
#include "bvh_alpha.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"

layout(local_size_x = kLightingGroup, local_size_y = kLightingGroup) in;
layout(set = 0, binding = kLightBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kLightBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kLightBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kLightBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kLightBindOut, rgba32f) uniform writeonly image2D out_direct;
layout(set = 0, binding = kLightBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
#ifdef GIB_LIGHTING_CLASSIFIED
layout(std430, set = 0, binding = kLightBindWorkloads) readonly buffer Workloads { uint wl[]; };
#endif
#ifdef GIB_LIGHTING_VRCS
layout(std430, set = 0, binding = kLightBindRates) buffer Rates { uint vrcs_rate_words[]; };
layout(set = 0, binding = kLightBindLuma, r32f) uniform writeonly image2D out_luma;
#include "renderer/techniques/deferred/include/vrcs.glsl"
#endif
layout(push_constant) uniform Push { LightPush push; };
#ifdef GIB_LIGHTING_SUN_VISIBILITY
// The shadow_mapped mode in a scene with a sun: its visibility from shadows_pcf (or the slot
// DirectLightingParams::sun_visibility names).
layout(set = 0, binding = kLightBindSunVisibility, r32f) uniform readonly image2D sun_visibility;
#define GIB_SUN_VISIBILITY(p) imageLoad(sun_visibility, p).x
#endif

#include "renderer/passes/direct_lighting/direct_light.glsl"

// The lit result at q; with VRCS also its tone-mapped luminance for next frame's rate.
void store_light(ivec2 q, vec3 result) {
  imageStore(out_direct, q, vec4(result, 1.0));
#ifdef GIB_LIGHTING_VRCS
  imageStore(out_luma, q, vec4(gib_vrcs_luma(result)));
#endif
}

void main() {
#ifdef GIB_LIGHTING_CLASSIFIED
  ivec2 p = gib_tile_list_pixel(wl[kTileHeader + kWorkload * push.tiles + gib_tile_list_entry()], push.tiles_x);
#else
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
#endif
  if (any(greaterThanEqual(p, imageSize(out_direct)))) return;
  vec3 result;
#ifdef GIB_LIGHTING_CLASSIFIED
  if (kWorkload == kWorkloadSky) {
    vec3 o, d;
    gib_camera_ray(vec2(p) + 0.5, o, d);
    result = gib_sky_radiance(d);
  } else {
#ifdef GIB_LIGHTING_VRCS
    // A pixel its coarse cell's anchor covers retires; the anchor lights itself and writes its
    // result to them (8x8 workgroups are the 8x8 rate tiles: one rate per workgroup).
    ivec2 cell;
    ivec2 size = imageSize(out_direct);
    ivec2 anchor = gib_vrcs_anchor(p, gib_vrcs_rate(p, push.rate_tiles_x), cell);
    if (gib_vrcs_follows(p, anchor, size)) return;
#endif
    result = gib_direct_light(p, push.sky_rays, push.nan_guards != 0u, kWorkload == kWorkloadTranslucent,
                              (kWorkload == kWorkloadCloth || kWorkload == kWorkloadTranslucent) && push.sheen_lobe != 0u);
#ifdef GIB_LIGHTING_VRCS
    uint covered = 0u;
    if (p == anchor)
      for (int y = 0; y < cell.y; ++y)
        for (int x = 0; x < cell.x; ++x) {
          ivec2 q = anchor + ivec2(x, y);
          if (!gib_vrcs_follows(q, anchor, size)) continue;
          store_light(q, result);
          ++covered;
        }
    bool geometry = imageLoad(vbuffer, p).x != kVisibilityNone;
    gib_vrcs_count(kVrcsStats + kVrcsStatLit, geometry ? 1u : 0u, geometry ? 1u + covered : 0u);  // kVrcsStatLitOf follows
#endif
  }
#else
  result = gib_direct_light(p, push.sky_rays, push.nan_guards != 0u, true, push.sheen_lobe != 0u);
#endif
  store_light(p, result);
}
