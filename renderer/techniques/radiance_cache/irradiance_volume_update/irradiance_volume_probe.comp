// irradiance_volume_update on GPUs: one 8x8 workgroup per probe of the updated cascade; the
// probe's rays are shaded once into group-shared memory, each thread convolves one interior
// texel, then the 10x10 tile with its border is written. CPU devices (lavapipe) use the
// barrier-free pair irradiance_volume_rays.comp + irradiance_volume_update.comp instead (same
// output): there each barrier costs ~70 us per workgroup, while on an H100 the split pair is
// 39% slower (0.108 vs 0.078 ms at ultra).
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
#include "hash.glsl"
#define GIB_ALPHA_SPEC kIvSpecAlpha
#include "bvh_alpha.glsl"
layout(constant_id = kIvSpecCacheFallback) const bool kCacheFallback = true;

layout(local_size_x = kIvGroup, local_size_y = kIvGroup) in;
layout(std430, set = 0, binding = kIvBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(set = 0, binding = kIvBindIrradiance, r32ui) uniform writeonly uimage2D out_irradiance;
layout(set = 0, binding = kIvBindVisibility, rg16f) uniform writeonly image2D out_visibility;
layout(push_constant) uniform Push { RcParams rc; };
#define RC_PROBE_RAYS
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kIvBindPrevIrradiance, kIvBindPrevVisibility)
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kIvBindCells, readonly)
#define IV_SHADE_RAYS
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_common.glsl"

const uint kTexels = kProbeTileInterior * kProbeTileInterior;
shared vec3 s_dir[kIvMaxRays];
shared vec3 s_radiance[kIvMaxRays];
shared float s_distance[kIvMaxRays];
shared uint s_irradiance[kTexels];
shared vec2 s_moments[kTexels];

void main() {
  uint probe = gl_WorkGroupID.x;
  uint tid = gl_LocalInvocationIndex;
  uint rays = min(rc_rays_per_probe(), kIvMaxRays);
  uint c = rc_updated_cascade();
  ivec3 ijk = rc_probe_coord(probe);
  vec3 o = rc_probe_position(c, ijk);
  mat3 rotation = rc_frame_rotation(rc.misc.x);
  float max_distance = rc_moment_max_distance(c);

  for (uint r = tid; r < rays; r += kTexels) {
    vec3 d = rc_ray_direction(r, rays, rotation);
    ProbeHit h = probe_hits[probe * rc_rays_per_probe() + r];
    vec3 l;
    // A ray that brings no light gets a zero direction (weight 0 in every texel); one inside
    // geometry a negative distance too, which the texels count.
    uint state = iv_ray_radiance(h, o, d, c, l);
    s_dir[r] = state == kIvRayLit ? d : vec3(0.0);
    s_radiance[r] = l;
    s_distance[r] = state == kIvRayInside ? -1.0 : min(h.distance, max_distance);
  }
  barrier();

  ivec2 texel = ivec2(gl_LocalInvocationID.xy);
  vec3 n = gib_oct_texel_direction(texel + 1, int(kProbeTileInterior));
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  vec2 moments = vec2(0.0);
  float moment_weight = 0.0;
  uint inside = 0u;
  for (uint r = 0u; r < rays; ++r) {
    inside += s_distance[r] < 0.0 ? 1u : 0u;
    float w = max(0.0, dot(n, s_dir[r]));
    sum += s_radiance[r] * w;
    weight += w;
    // w^16 (kIvDistanceSharpness) by four squarings: pow() is a log/exp pair per ray and texel.
    float w2 = w * w, w4 = w2 * w2, w8 = w4 * w4, wd = w8 * w8;
    float dist = s_distance[r];
    moments += wd * vec2(dist, dist * dist);
    moment_weight += wd;
  }
  vec3 irradiance = weight > 0.0 ? sum / weight : vec3(0.0);
  moments = moment_weight > 0.0 ? moments / moment_weight : vec2(max_distance, max_distance * max_distance);

  uvec2 origin = rc_tile_origin(c, rc_probe_slot(c, ijk));
  ivec2 at = ivec2(origin) + texel + 1;
  iv_finish_texel(at, inside, rays, irradiance, moments);
  s_irradiance[tid] = iv_pack_irradiance(at, irradiance);
  s_moments[tid] = moments;
  barrier();

  for (uint t = tid; t < kProbeTileSize * kProbeTileSize; t += kTexels) {
    ivec2 local = ivec2(t % kProbeTileSize, t / kProbeTileSize);
    ivec2 src = gib_oct_border_source(local, int(kProbeTileInterior)) - 1;
    uint si = uint(src.y) * kProbeTileInterior + uint(src.x);
    imageStore(out_irradiance, ivec2(origin) + local, uvec4(s_irradiance[si]));
    imageStore(out_visibility, ivec2(origin) + local, vec4(s_moments[si], 0.0, 0.0));
  }
}
