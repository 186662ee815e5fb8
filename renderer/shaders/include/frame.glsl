// Frame constants (binding 0) and camera-ray helpers. See frame_shared.h.
#ifndef GIB_FRAME_GLSL
#define GIB_FRAME_GLSL
#include "frame_shared.h"

layout(set = 0, binding = 0, std140) uniform GibFrameBlock { GpuFrame gib_frame; };

uint gib_frame_index() { return gib_frame.frame_info.x; }
uvec2 gib_render_size() { return gib_frame.frame_info.yz; }
uint gib_light_count() { return gib_frame.frame_info.w; }
uint gib_seed() { return gib_frame.scene_info.z; }
uint gib_decal_count() { return gib_frame.scene_info.w; }
// Inside one of the scene's indoor volumes (Scene::indoor_volumes; none: false).
bool gib_indoor(vec3 x) {
  for (uint i = 0u; i < gib_frame.volume_info.x; ++i)
    if (all(greaterThanEqual(x, gib_frame.indoor_min[i].xyz)) && all(lessThanEqual(x, gib_frame.indoor_max[i].xyz))) return true;
  return false;
}

// World-space ray through a position in pixel units (0..width, 0..height). The direction comes
// from the camera-relative inverse, so it is as precise 10 km from the origin as at it.
void gib_camera_ray(vec2 pixel, out vec3 origin, out vec3 dir) {
  vec2 ndc = pixel / vec2(gib_render_size()) * 2.0 - 1.0;
  vec4 far_h = gib_frame.inv_view_proj_rel * vec4(ndc, 1.0, 1.0);
  origin = gib_frame.camera_pos.xyz;
  dir = normalize(far_h.xyz / far_h.w);
}
#endif
