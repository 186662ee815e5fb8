// The direct_lighting pass's kernel, shared by direct_lighting.comp (the sun shadowed by a ray
// per pixel) and direct_lighting_sun_visibility.comp (GIB_DIRECT_SUN_VISIBILITY: by a slot).
// Included after #version; not a kernel of its own.
#include "renderer/passes/direct_lighting/direct_lighting_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
layout(constant_id = kDirectSpecSun) const bool kHasSun = true;
layout(constant_id = kDirectSpecSky) const bool kHasSky = true;
layout(constant_id = kDirectSpecLocal) const bool kHasLocal = true;
layout(constant_id = kDirectSpecEmissive) const bool kHasEmissive = true;
layout(constant_id = kDirectSpecSkyUnoccluded) const bool kSkyUnoccluded = false;
#define GIB_ALPHA_SPEC kDirectSpecAlpha
#include "bvh_alpha.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"

layout(local_size_x = kDirectGroup, local_size_y = kDirectGroup) in;
layout(set = 0, binding = kDirectBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kDirectBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kDirectBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kDirectBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kDirectBindOut, rgba32f) uniform writeonly image2D out_direct;
layout(set = 0, binding = kDirectBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(push_constant) uniform Push { DirectPush push; };
#ifdef GIB_DIRECT_SUN_VISIBILITY
// The sun is shadowed by the visibility a shadow pass wrote (DirectLightingParams::sun_visibility).
layout(set = 0, binding = kDirectBindSunVisibility, r32f) uniform readonly image2D sun_visibility;
#define GIB_SUN_VISIBILITY(p) imageLoad(sun_visibility, p).x
#endif

#include "renderer/passes/direct_lighting/direct_light.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_direct)))) return;
  // Alpha: the fraction of the pixel's sky rays that met a surface (direct_light.glsl).
  float sky_hits;
  vec3 direct = gib_direct_light(p, push.sky_rays, push.nan_guards != 0u, true, true, sky_hits);
  imageStore(out_direct, p, vec4(direct, sky_hits));
}
