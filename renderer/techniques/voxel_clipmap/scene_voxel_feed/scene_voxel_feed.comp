// scene_voxel_feed: stochastic G-buffer pixels lit and averaged into the scene voxels (see
// scene_voxel_feed.h); two kernels chosen by kKernel: claim, then write.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/scene_voxel_feed/scene_voxel_feed_shared.h"
#include "frame.glsl"
#include "vbuffer_shared.h"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "packing.glsl"
#include "finite.glsl"
layout(constant_id = kScFeedSpecKernel) const uint kKernel = 0u;
layout(push_constant) uniform Push {
  VcParams vc;
  uvec4 moving[2];
};
VC_STATE_BUFFER(kScFeedBindState, )
VC_VOXEL_BUFFER(kScFeedBindVoxels, )
VC_THIRD_BUFFER(kScFeedBindThird, readonly)
VC_VIS_BUFFER(kScFeedBindVis, readonly)
layout(std430, set = 0, binding = kScFeedBindOwner) buffer OwnerBuffer { uint owner[]; };
VC_CUBE_BUFFERS(kScFeedBindX, kScFeedBindY, kScFeedBindZ, kScFeedBindCells, readonly)
layout(set = 0, binding = kScFeedBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kScFeedBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kScFeedBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kScFeedBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kScFeedBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kScFeedBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
#define VC_HAS_STATE
#define VC_HAS_CUBES
#define VC_CONVEX_VOXELS
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"
layout(local_size_x = kScFeedGroup) in;

// The sample's pixel, or false for a pixel that feeds nothing (sky, moving object, broken data).
bool sample_pixel(uint i, out ivec2 p, out vec3 x, out uint instance) {
  uvec2 size = gib_render_size();
  GibRng rng = gib_rng(vc.rays.z, vc_frame(), uvec2(i, 0u), 17u);
  p = ivec2(min(uvec2(gib_next2(rng) * vec2(size)), size - 1u));
  uvec2 ids = imageLoad(vbuffer, p).xy;
  instance = ids.y;
  if (ids.x == kVisibilityNone) return false;
  for (uint k = 0u; k < kScFeedMaxMoving; ++k)
    if (moving[k / 4u][k % 4u] == ids.y) return false;
  vec4 pos = imageLoad(gb_position, p);
  x = pos.xyz;
  return pos.w > 0.0 && gib_finite(x);
}

// The voxel of level l a surface point feeds: the one on its normal's side (a wall on a voxel
// boundary fills the voxels on both sides; rays from the side it faces meet the near one).
ivec3 vc_feed_voxel(vec3 x, vec3 n, uint l) {
  float s = vc_voxel_size(l);
  return ivec3(floor((x + n * (1e-3 * s)) / s));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= vc.budget.x) return;
  ivec2 p;
  vec3 x;
  uint instance;
  if (!sample_pixel(i, p, x, instance)) return;
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (vc_flag(kVcFlagNanGuards) && !(gib_finite(n) && dot(n, n) > 0.25)) return;
  if (kKernel == kScFeedClaim) {
    for (uint l = 0u; l < vc_levels(); ++l) {
      ivec3 g = vc_feed_voxel(x, n, l);
      if (vc_in_box(g, vc_voxel_origin(l), vc_n())) atomicMax(owner[vc_voxel_index(l, g)], i + 1u);
    }
    return;
  }
  // kScFeedWrite: light the pixel once, write the voxels this sample owns. Most samples own
  // none (several samples a voxel): those return before the lighting.
  bool owns = false;
  for (uint l = 0u; l < vc_levels() && !owns; ++l) {
    ivec3 g = vc_feed_voxel(x, n, l);
    owns = vc_in_box(g, vc_voxel_origin(l), vc_n()) && owner[vc_voxel_index(l, g)] == i + 1u;
  }
  if (!owns) return;
  vec3 albedo = imageLoad(gb_albedo, p).rgb;
  vec3 emitted = imageLoad(gb_emissive, p).rgb;
  // direct_light holds the emission too; the voxel keeps it apart (relit cells count it as
  // direct light, the AOV contract's: emission reaching a surface with no further bounce).
  vec4 direct_hits = imageLoad(direct_light, p);
  vec3 direct = max(direct_hits.rgb - emitted, vec3(0.0));
  if (vc_flag(kVcFlagNanGuards) && !gib_finite(direct)) return;
  vec3 bounce, sky;
  // With the wall test of VC_CONVEX_VOXELS (geometry_light): it reads the geometry flag, which
  // this kernel keeps, not the opacities it writes, so thread timing does not matter.
  float hit;
  vc_irradiance(x, n, vc_flag(kVcFlagConvexOffset), bounce, sky, hit);
  // The pixel's sky rays counted the sky where they escaped: bounce over the share that met a
  // surface (as irradiance_shade), so the voxel holds the pixel's radiance with no direction twice.
  if (vc_flag(kVcFlagPixelSkyHits)) bounce = vc_bounce_for_pixel(bounce, hit, direct_hits.a);
  if (!vc_flag(kVcFlagMultiBounce)) bounce = vec3(0.0);
  vec3 radiance = direct + albedo * (bounce + (vc_flag(kVcFlagSkyFromCubes) ? sky : vec3(0.0)));
  if (vc_flag(kVcFlagNanGuards) && !(gib_finite(radiance) && gib_finite(emitted))) return;
  GpuMaterial m = gib_materials[gib_instances[instance].material];
  float opacity = (m.alpha != GIB_ALPHA_NONE && vc_flag(kVcFlagSemiTransparent)) ? m.avg_opacity : 1.0;
  bool opaque = opacity >= 1.0;
  for (uint l = 0u; l < vc_levels(); ++l) {
    ivec3 g = vc_feed_voxel(x, n, l);
    if (!vc_in_box(g, vc_voxel_origin(l), vc_n())) continue;
    uint idx = vc_voxel_index(l, g);
    if (owner[idx] != i + 1u) continue;
    uvec4 v = vc_voxels[idx];
    bool fed = (v.y & kVcVoxelFed) != 0u;
    float a = fed ? vc.sizes.y : 1.0;
    vec3 rad = mix(gib_unpack_rgb9e5(v.x), radiance, a);
    vec3 em = mix(gib_unpack_rgb9e5(v.z), emitted, a);
    float old_op = float(v.y & kVcOpacityMask) / 255.0;
    // A semi-transparent pixel does not thin a voxel that opaque surfaces fed (4.4).
    float op = (!opaque && (v.y & kVcVoxelOpaqueFed) != 0u) ? old_op : mix(old_op, opacity, a);
    uint op8 = vc_opacity_byte(op);
    uint flags = (v.y & (kVcVoxelGeometry | kVcVoxelNew | kVcVoxelOpaqueFed | ~((1u << kVcSecondLowShift) - 1u))) | kVcVoxelFed | (opaque ? kVcVoxelOpaqueFed : 0u);
    // Stochastic rounding (a dither from the voxel, the frame and the seed): rounded to nearest,
    // a blend that moves by less than half a unit a frame stops, a bias the loop multiplies.
    uint dither = gib_pcg(idx ^ gib_pcg(vc_frame() ^ gib_pcg(vc.rays.z ^ 0x5bd1e995u)));
    vc_voxels[idx] = uvec4(gib_pack_rgb9e5_dither(rad, dither), flags | op8, gib_pack_rgb9e5_dither(em, gib_pcg(dither)), v.w);
    atomicAdd(vc_state.stats.y, 1u);
  }
}
