// irradiance_volume_update on GPUs: one 8x8 workgroup per probe of the updated cascade; the
// probe's rays are shaded once into group-shared memory, each thread convolves one interior
// texel, then the 10x10 tile with its border is written; each group also carries one tile of
// the cascade last frame updated (carry_load / carry_store). CPU devices (lavapipe) use the
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
// Which probes this dispatch updates and whether it has the cache fallback's code (kIvPass*,
// irradiance_volume_update_shared.h). The fallback (a surface, a material and a volume sample with
// up to 8 shadow rays) sets the kernel's register count, although a steady frame's rays all find
// their cell: kIvPassCached leaves it out, and the few probes that need it run again in
// kIvPassFallback.
layout(constant_id = kIvSpecPass) const uint kIvPass = kIvPassAll;
#define IV_DEFER_FALLBACK (kIvPass == kIvPassCached)

layout(local_size_x = kIvGroup, local_size_y = kIvGroup) in;
layout(std430, set = 0, binding = kIvBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(set = 0, binding = kIvBindIrradiance, r32ui) uniform writeonly uimage2D out_irradiance;
layout(set = 0, binding = kIvBindVisibility, rg16f) uniform writeonly image2D out_visibility;
// The probes whose rays missed the cache, this frame's list (kIvPassCached appends, kIvPassFallback
// reads) and last frame's (kIvPassCached resets it for the next frame). Bound by both passes only.
layout(std430, set = 0, binding = kIvBindFallback) buffer Fallback { uint iv_fallback[]; };
layout(std430, set = 0, binding = kIvBindNextFallback) buffer NextFallback { uint iv_next_fallback[]; };
layout(push_constant) uniform Push { RcParams rc; uvec4 iv_extra; };
#define RC_PROBE_RAYS
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kIvBindPrevIrradiance, kIvBindPrevVisibility)
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kIvBindCells, readonly)
#define IV_SHADE_RAYS
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_common.glsl"

const uint kTexels = kProbeTileInterior * kProbeTileInterior;
// Rays per probe (rays_per_probe, at most kIvMaxRays): sizes the group-shared ray arrays, so a
// group reserves what its rays need (2 KB at 64 rays instead of 8 KB at 256: more groups fit an
// SM, and on NVIDIA shared memory is carved out of the L1 the cache lookups use), and is the
// texel loop's trip count.
layout(constant_id = kIvSpecRays) const uint kRays = kIvMaxRays;
// Per ray, two 16-byte words the texel loop reads with one load each: direction (zero when the
// ray brings no light) and distance (-1 inside geometry); radiance.
shared vec4 s_dir_distance[kRays];
shared vec4 s_radiance[kRays];
shared uint s_inside;  // rays of the probe inside geometry (the same for every texel)
shared uint s_missed;  // kIvPassCached: rays of the probe whose hit has no shaded cell
shared uint s_irradiance[kTexels];
shared vec2 s_moments[kTexels];

// The carry (irradiance_volume_carry.comp's job on the split path), folded into this dispatch:
// group g copies tile g of the carried cascade's rows from last frame's copy, which this
// dispatch only reads, to this frame's, whose other cascade it writes. No extra dispatch or
// barrier, no extra group. The loads are issued first and stored after the rays' barrier, so
// their latency hides behind the rays' own loads.
const uint kCarryPerThread = (kProbeTileSize * kProbeTileSize + kProbeTileInterior * kProbeTileInterior - 1u) /
                             (kProbeTileInterior * kProbeTileInterior);
struct CarryTexels {
  ivec2 at[kCarryPerThread];
  uint irradiance[kCarryPerThread];
  vec2 moments[kCarryPerThread];
  bool copy[kCarryPerThread];
};

CarryTexels carry_load(uint g, uint tid) {
  CarryTexels c;
  uint cascade = iv_extra.x;
  const uint tiles_per_row = kProbeAtlasWidth / kProbeTileSize;
  ivec2 origin = ivec2(int((g % tiles_per_row) * kProbeTileSize),
                       int(cascade * kProbeAtlasRowsPerCascade + (g / tiles_per_row) * kProbeTileSize));
  for (uint k = 0u; k < kCarryPerThread; ++k) {
    uint t = tid + k * kProbeTileInterior * kProbeTileInterior;
    // The carry is the dispatch over every probe's (one tile per group); the fallback pass has none.
    c.copy[k] = kIvPass != kIvPassFallback && cascade != kIvNoCarry && t < kProbeTileSize * kProbeTileSize;
    c.at[k] = origin + ivec2(int(t % kProbeTileSize), int(t / kProbeTileSize));
    c.irradiance[k] = c.copy[k] ? rc_probe_irradiance_texel(c.at[k]) : 0u;
    c.moments[k] = c.copy[k] ? rc_probe_visibility_texel(c.at[k]) : vec2(0.0);
  }
  return c;
}

void carry_store(CarryTexels c) {
  for (uint k = 0u; k < kCarryPerThread; ++k)
    if (c.copy[k]) {
      imageStore(out_irradiance, c.at[k], uvec4(c.irradiance[k]));
      imageStore(out_visibility, c.at[k], vec4(c.moments[k], 0.0, 0.0));
    }
}

void main() {
  uint tid = gl_LocalInvocationIndex;
  if (kIvPass == kIvPassCached && gl_WorkGroupID.x == 0u && tid == 0u) {
    // This frame's list starts as the previous user of its copy left it (x = 0) or zeroed (the
    // first frame): y and z of the indirect dispatch are set here; last frame's copy, which no
    // one reads any more, is reset for the next frame.
    iv_fallback[1] = 1u;
    iv_fallback[2] = 1u;
    iv_next_fallback[0] = 0u;
    iv_next_fallback[1] = 1u;
    iv_next_fallback[2] = 1u;
  }
  uint probe = kIvPass == kIvPassFallback ? iv_fallback[kIvFallbackListFirst + gl_WorkGroupID.x] : gl_WorkGroupID.x;
  CarryTexels carried = carry_load(probe, tid);
  const uint rays = kRays;  // rc_rays_per_probe(), as a constant
  uint c = rc_updated_cascade();
  ivec3 ijk = rc_probe_coord(probe);
  vec3 o = rc_probe_position(c, ijk);
  mat3 rotation = rc_frame_rotation(rc.misc.x);
  float max_distance = rc_moment_max_distance(c);

  if (tid == 0u) {
    s_inside = 0u;
    s_missed = 0u;
  }
  barrier();
  for (uint r = tid; r < rays; r += kTexels) {
    vec3 d = rc_ray_direction(r, rays, rotation);
    ProbeHit h = probe_hits[probe * rc_rays_per_probe() + r];
    vec3 l;
    // A ray that brings no light gets a zero direction (weight 0 in every texel); one inside
    // geometry a negative distance too, and is counted.
    uint state = iv_ray_radiance(h, o, d, c, l);
    s_dir_distance[r] = vec4(state == kIvRayLit ? d : vec3(0.0), state == kIvRayInside ? -1.0 : min(h.distance, max_distance));
    s_radiance[r] = vec4(l, 0.0);
    if (state == kIvRayInside) atomicAdd(s_inside, 1u);
    if (state == kIvRayMissed) atomicAdd(s_missed, 1u);
  }
  barrier();
  carry_store(carried);
  if (kIvPass == kIvPassCached && s_missed != 0u) {
    // Leave the probe to the fallback pass (the same for every thread of the group).
    if (tid == 0u) iv_fallback[kIvFallbackListFirst + atomicAdd(iv_fallback[0], 1u)] = probe;
    return;
  }

  ivec2 texel = ivec2(gl_LocalInvocationID.xy);
  uvec2 origin = rc_tile_origin(c, rc_probe_slot(c, ijk));
  ivec2 at = ivec2(origin) + texel + 1;
  IvLastFrame last = iv_load_last_frame(at);  // waited for only after the ray loop
  vec3 n = gib_oct_texel_direction(texel + 1, int(kProbeTileInterior));
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  vec2 moments = vec2(0.0);
  float moment_weight = 0.0;
  for (uint r = 0u; r < rays; ++r) {
    vec4 dd = s_dir_distance[r];
    float w = max(0.0, dot(n, dd.xyz));
    sum += s_radiance[r].rgb * w;
    weight += w;
    // w^16 (kIvDistanceSharpness) by four squarings: pow() is a log/exp pair per ray and texel.
    float w2 = w * w, w4 = w2 * w2, w8 = w4 * w4, wd = w8 * w8;
    float dist = dd.w;
    moments += wd * vec2(dist, dist * dist);
    moment_weight += wd;
  }
  uint inside = s_inside;
  vec3 irradiance = weight > 0.0 ? sum / weight : vec3(0.0);
  moments = moment_weight > 0.0 ? moments / moment_weight : vec2(max_distance, max_distance * max_distance);

  iv_finish_texel(last, inside, rays, irradiance, moments);
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
