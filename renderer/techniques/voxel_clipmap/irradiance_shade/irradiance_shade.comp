// irradiance_shade: bounce and sky irradiance / pi per pixel from the ambient-cube clipmap (see
// irradiance_shade.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/irradiance_shade/irradiance_shade_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "finite.glsl"
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kIrrShadeBindState, readonly)
VC_CUBE_BUFFERS(kIrrShadeBindX, kIrrShadeBindY, kIrrShadeBindZ, kIrrShadeBindCells, readonly)
VC_VOXEL_BUFFER(kIrrShadeBindVoxels, readonly)
VC_THIRD_BUFFER(kIrrShadeBindThird, readonly)
VC_VIS_BUFFER(kIrrShadeBindVis, readonly)
layout(set = 0, binding = kIrrShadeBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kIrrShadeBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kIrrShadeBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kIrrShadeBindBounce, rgba32f) uniform writeonly image2D out_bounce;
layout(set = 0, binding = kIrrShadeBindSky, rgba32f) uniform writeonly image2D out_sky;
#define VC_HAS_STATE
#define VC_HAS_CUBES
#define VC_CONVEX_VOXELS
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kIrrShadeGroup, local_size_y = kIrrShadeGroup) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_bounce)))) return;
  vec4 pos = imageLoad(gb_position, p);
  vec3 bounce = vec3(0.0), sky = vec3(0.0);
  if (pos.w > 0.0) {
    vec3 n = imageLoad(gb_normal, p).xyz;
    if (vc_flag(kVcFlagNanGuards) && !(gib_finite(n) && dot(n, n) > 0.25)) {
      // Guard: a broken normal is lit as if it faced the camera (as direct_lighting does).
      vec3 o, d;
      gib_camera_ray(vec2(p) + 0.5, o, d);
      n = -d;
    }
    float hit;
    vc_irradiance(pos.xyz, normalize(n), vc_flag(kVcFlagConvexOffset), bounce, sky, hit);
    // The pixel's sky rays counted the sky where they escaped: bounce over the share that met a surface.
    if (vc_flag(kVcFlagPixelSkyHits)) bounce = vc_bounce_for_pixel(bounce, hit, imageLoad(direct_light, p).a);
  }
  imageStore(out_bounce, p, vec4(bounce, 1.0));
  imageStore(out_sky, p, vec4(vc_flag(kVcFlagSkyFromCubes) ? sky : vec3(0.0), 1.0));
}
