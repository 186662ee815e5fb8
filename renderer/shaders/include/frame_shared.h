// Per-frame constants (a uniform buffer at binding 0 of every pass that uses the scene),
// written by the executor, read by passes through frame.glsl.
#ifndef GIB_FRAME_SHARED_H
#define GIB_FRAME_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN

// Binding numbers of the scene bundle: frame constants, then the buffers scene.glsl declares.
GIB_CONST(uint, kBindFrame, 0)
GIB_CONST(uint, kBindSceneFirst, 1)  // vertices, triangles, instances, materials, bvh nodes, bvh tri index, lights
GIB_CONST(uint, kSceneBufferCount, 7)
GIB_CONST(uint, kBindPassFirst, 8)   // a pass's own slots start here
GIB_CONST(uint, kBindSceneTextures, 31)  // packed image textures: kBindSceneFirst + GIB_SCENE_BINDING_TEXTURES

GIB_CONST(uint, kMaxDecals, 16)  // decals a scene may have (scene.h kMaxDecals; loader limit)
GIB_CONST(uint, kMaxIndoorVolumes, 8)  // indoor volumes a scene may have (scene.h kMaxIndoorVolumes)

// A box-projected decal (renderer/scene/scene.h GpuDecal, decals.glsl): a point x lies at box
// coordinates l_i = dot(axis_i.xyz, x - centre.xyz) * axis_i.w, inside when all |l_i| <= 0.5.
struct GpuDecal {
  vec4 centre;  // xyz, w: shape (0 rect, 1 disc)
  vec4 axis_x;  // unit axis, w: 1 / size
  vec4 axis_y;
  vec4 axis_z;  // surfaces facing +axis_z receive the decal
  vec4 albedo;  // rgb, a: opacity
};

struct GpuFrame {
  mat4 view_proj;
  mat4 inv_view_proj_rel;  // inverse of view_proj without the camera translation: NDC -> offset from camera_pos
  mat4 prev_view_proj;
  vec4 camera_pos;      // xyz, w: tan(fov_y / 2)
  vec4 sun_dir;         // xyz towards the sun, w: cos(angular radius)
  vec4 sun_irradiance;  // rgb W/m^2, w: 1 when the sun is on
  vec4 sky_zenith;      // rgb, w: SkyKind
  vec4 sky_horizon;     // rgb, w: turbidity
  vec4 sky_ground;      // rgb, w: unused
  uvec4 frame_info;     // frame index, render width, render height, light count
  uvec4 scene_info;     // triangle count, instance count, seed, decal count
  uvec4 alpha_info;     // alpha strategy (AlphaStrategy), any-hit limit (0: none), unused, unused
  GpuDecal decals[kMaxDecals];
  uvec4 volume_info;                      // x: indoor volume count (Scene::indoor_volumes), y-w: unused
  vec4 indoor_min[kMaxIndoorVolumes];     // xyz: box minimum corner (world space)
  vec4 indoor_max[kMaxIndoorVolumes];     // xyz: box maximum corner
};

GIB_SHARED_END
#endif
