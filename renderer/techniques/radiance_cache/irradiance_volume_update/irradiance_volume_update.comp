// irradiance_volume_update, step 2: one invocation per texel of the updated cascade's 10x10
// tiles (border texels included: each computes the interior texel it mirrors, so no
// group-shared memory or barrier is needed). Cosine-convolves the probe's rays
// (probe_ray_radiance, written by irradiance_volume_rays.comp) into irradiance / pi for the
// texel's direction and power-weighted distance moments, blends with last frame
// (hysteresis), stores RGB9E5 irradiance and RG16F moments.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "material.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"

layout(local_size_x = kIvConvolveGroup) in;
layout(std430, set = 0, binding = kIvBindRays) readonly buffer RayBuffer { vec4 probe_ray_radiance[]; };
layout(set = 0, binding = kIvBindIrradiance, r32ui) uniform writeonly uimage2D out_irradiance;
layout(set = 0, binding = kIvBindVisibility, rg16f) uniform writeonly image2D out_visibility;
layout(push_constant) uniform Push { RcParams rc; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kIvBindPrevIrradiance, kIvBindPrevVisibility)
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_common.glsl"

void main() {
  const uint kTileTexels = kProbeTileSize * kProbeTileSize;
  uint i = gl_GlobalInvocationID.x;
  if (i >= kProbeGridDim * kProbeGridDim * kProbeGridDim * kTileTexels) return;
  uint probe = i / kTileTexels, t = i % kTileTexels;
  uint rays = rc_rays_per_probe();
  uint c = rc_updated_cascade();
  ivec3 ijk = rc_probe_coord(probe);
  mat3 rotation = rc_frame_rotation(rc.misc.x);
  float max_distance = rc_moment_max_distance(c);
  ivec2 local = ivec2(t % kProbeTileSize, t / kProbeTileSize);
  ivec2 texel = gib_oct_border_source(local, int(kProbeTileInterior)) - 1;  // interior texel it shows

  uvec2 origin = rc_tile_origin(c, rc_probe_slot(c, ijk));
  ivec2 at = ivec2(origin) + texel + 1;
  IvLastFrame last = iv_load_last_frame(at);
  vec3 n = gib_oct_texel_direction(texel + 1, int(kProbeTileInterior));
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  vec2 moments = vec2(0.0);
  float moment_weight = 0.0;
  uint inside = 0u;
  for (uint r = 0u; r < rays; ++r) {
    vec4 ray = probe_ray_radiance[probe * rays + r];
    if (ray.w < 0.0) {  // dropped by the guard, or inside geometry
      inside += ray.w == kIvInsideMark ? 1u : 0u;
      continue;
    }
    // Recomputed rather than stored: on lavapipe a second buffer load per ray costs more.
    float w = max(0.0, dot(n, rc_ray_direction(r, rays, rotation)));
    sum += ray.rgb * w;
    weight += w;
    // w^16 (kIvDistanceSharpness) by four squarings: pow() is a log/exp pair per ray and texel.
    float w2 = w * w, w4 = w2 * w2, w8 = w4 * w4, wd = w8 * w8;
    moments += wd * vec2(ray.w, ray.w * ray.w);
    moment_weight += wd;
  }
  vec3 irradiance = weight > 0.0 ? sum / weight : vec3(0.0);
  moments = moment_weight > 0.0 ? moments / moment_weight : vec2(max_distance, max_distance * max_distance);

  iv_finish_texel(last, inside, rays, irradiance, moments);
  imageStore(out_irradiance, ivec2(origin) + local, uvec4(iv_pack_irradiance(at, irradiance)));
  imageStore(out_visibility, ivec2(origin) + local, vec4(moments, 0.0, 0.0));
}
