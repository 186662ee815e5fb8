// scene_voxel_light: unfed geometry voxels lit from their triangle (see scene_voxel_light.h).
// One thread per visited voxel; each writes only its own voxel, so the result does not depend
// on thread order.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/scene_voxel_light/scene_voxel_light_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kScLightSpecAlpha
#include "bvh_alpha.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "packing.glsl"
#include "finite.glsl"
layout(constant_id = kScLightSpecSun) const bool kHasSun = true;
layout(constant_id = kScLightSpecLocal) const bool kHasLocal = true;
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kScLightBindState, readonly)
VC_VOXEL_BUFFER(kScLightBindVoxels, )
VC_THIRD_BUFFER(kScLightBindThird, readonly)
VC_VIS_BUFFER(kScLightBindVis, readonly)
VC_CUBE_BUFFERS(kScLightBindX, kScLightBindY, kScLightBindZ, kScLightBindCells, readonly)
#define VC_HAS_STATE
#define VC_HAS_CUBES
#define VC_CONVEX_VOXELS
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
#include "renderer/techniques/voxel_clipmap/include/vc_voxelize.glsl"
layout(local_size_x = kScLightGroup) in;

// Irradiance-like light (x pi / albedo: the caller multiplies by albedo / pi) from the sun and
// the local lights at x with normal n, each behind one shadow ray.
vec3 direct_light(vec3 x, vec3 n) {
  vec3 sum = vec3(0.0);
  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
    vec3 wi = gib_frame.sun_dir.xyz;
    float c = dot(n, wi);
    if (c > 0.0 && !trace_any(gib_offset_ray(x, n), wi, 0.0, 3.4e38)) sum += c * gib_frame.sun_irradiance.rgb;
  }
  if (kHasLocal) {
    for (uint i = 0u; i < gib_light_count(); ++i) {
      vec3 wi;
      float dist;
      vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
      float c = dot(n, wi);
      if (c <= 0.0 || all(equal(e, vec3(0.0)))) continue;
      if (!trace_any(gib_offset_ray(x, n), wi, 0.0, dist * 0.999)) sum += c * e;
    }
  }
  return sum;
}

void main() {
  uint total = vc_levels() * vc_voxels_per_level();
  uint visits = clamp(vc.rays.w, 1u, total);
  if (gl_GlobalInvocationID.x >= visits) return;
  // The window of this frame: the atlas cut into windows of `visits` voxels, one a frame in turn.
  uint windows = (total + visits - 1u) / visits;
  uint idx = (vc_frame() % windows) * visits + gl_GlobalInvocationID.x;
  if (idx >= total) return;
  uvec4 v = vc_voxels[idx];
  uint tri = v.w & kVcFillTriangleMask;
  if ((v.y & kVcVoxelGeometry) == 0u || (v.y & kVcVoxelFed) != 0u || tri == 0u) return;
  tri -= 1u;
  if (tri >= gib_frame.scene_info.x) return;
  uint l = idx / vc_voxels_per_level(), slot = idx % vc_voxels_per_level();
  int n = vc_n();
  ivec3 s = ivec3(int(slot) % n, (int(slot) / n) % n, int(slot) / (n * n));
  vec3 centre = (vec3(vc_slot_world(s, vc_voxel_origin(l), n)) + 0.5) * vc_voxel_size(l);
  GpuTriangle t = gib_triangles[tri];
  vec3 a = gib_vertices[t.i0].position, b = gib_vertices[t.i1].position, c = gib_vertices[t.i2].position;
  vec2 uv = vc_closest_on_triangle(centre, a, b, c);
  // A point on the triangle's edge is where it meets other geometry (a floor under a wall): its
  // shadow rays could start outside that geometry. Moved a tenth of a voxel towards the
  // centroid, it lies inside the surface's own extent.
  vec3 p = a + (b - a) * uv.x + (c - a) * uv.y, toward = (a + b + c) / 3.0 - p;
  float len = length(toward);
  if (len > 0.0) uv += (vec2(1.0 / 3.0) - uv) * min(1.0, 0.1 * vc_voxel_size(l) / len);
  GibSurface surf = gib_surface(tri, uv.x, uv.y, vc_flag(kVcFlagNanGuards));
  if (!gib_finite(surf.position) || !gib_finite(surf.normal)) return;
  GpuMaterial m = gib_materials[surf.material];
  vec3 albedo = gib_material_albedo(m, surf.uv);
  vec3 emitted = gib_material_emissive(m, surf.uv);
  vec3 bounce, sky;
  float hit;
  vc_irradiance(surf.position, surf.normal, vc_flag(kVcFlagConvexOffset), bounce, sky, hit);
  if (!vc_flag(kVcFlagMultiBounce)) bounce = vec3(0.0);
  vec3 radiance = albedo * (direct_light(surf.position, surf.normal) / GIB_PI + bounce + sky);
  if (vc_flag(kVcFlagNanGuards) && !(gib_finite(radiance) && gib_finite(emitted))) return;
  // Stochastic rounding, as the feed's: a voxel lit to the same value each visit would round
  // the same way every time, a bias the loop multiplies.
  uint dither = gib_pcg(idx ^ gib_pcg(vc_frame() ^ gib_pcg(vc.rays.z ^ 0x27d4eb2fu)));
  vc_voxels[idx] = uvec4(gib_pack_rgb9e5_dither(radiance, dither), v.y | kVcVoxelLit,
                         gib_pack_rgb9e5_dither(emitted, gib_pcg(dither)), v.w);
}
