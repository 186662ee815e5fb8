#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// final_gather: one cosine-distributed ray per gather pixel, answered only from caches
// (screen, world, irradiance volumes, sky), projected into 2-band SH per colour channel.
// See final_gather.h for the conventions.
#include "renderer/techniques/radiance_cache/final_gather/final_gather_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#define GIB_ALPHA_SPEC kGatherSpecAlpha
#include "bvh_alpha.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "sh.glsl"
#include "finite.glsl"

layout(push_constant) uniform Push {
  RcParams rc;
  GatherPush push;
};
#define RC_PROBE_RAYS
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
RC_PROBE_IMAGES(kGatherBindProbeIrradiance, kGatherBindProbeVisibility)
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
RC_CELL_BUFFER(kGatherBindCells, readonly)

layout(local_size_x = kGatherGroup, local_size_y = kGatherGroup) in;
layout(set = 0, binding = kGatherBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kGatherBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kGatherBindPrevPosition, rgba32f) uniform readonly image2D prev_position;
layout(set = 0, binding = kGatherBindPrevColor, rgba32f) uniform readonly image2D prev_color;
layout(set = 0, binding = kGatherBindStats, std430) buffer GatherStats { uint gather_stats[kGatherStatCount]; };
layout(set = 0, binding = kGatherBindShR, rgba16f) uniform writeonly image2D out_sh_r;
layout(set = 0, binding = kGatherBindShG, rgba16f) uniform writeonly image2D out_sh_g;
layout(set = 0, binding = kGatherBindShB, rgba16f) uniform writeonly image2D out_sh_b;
layout(set = 0, binding = kGatherBindHitDistance, r32f) uniform writeonly image2D out_hit;
layout(set = 0, binding = kGatherBindDirect, rgba16f) uniform writeonly image2D out_direct;
layout(set = 0, binding = kGatherBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
// Pre-exposure (exposure pass): float[4], P this frame at kGatherExposureNow.
layout(set = 0, binding = kGatherBindExposure, std430) readonly buffer Exposure { float exposure[4]; };

const float kFar = 3.4e38;
// RGBA16F's largest finite value: SH coefficients are clamped to it so they stay finite in the
// store, and a clamped one is exactly the format's maximum, which the stability scan counts as
// 'Value at format maximum' (a clamp just below it would hide the saturation).
const float kHalfMax = 65504.0;

// Screen cache: last frame's shaded colour at the hit, if the hit was on screen and visible.
// Visibility: the hit's view depth under prev_view_proj (clip w) matches, within a relative
// tolerance, the depth of last frame's G-buffer sample at the pixel the hit projects to, and
// the ray hit the side of the surface that faces the camera.
bool screen_cache(vec3 x, vec3 n_hit, out vec3 radiance) {
  radiance = vec3(0.0);
  vec4 clip = gib_frame.prev_view_proj * vec4(x, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 ndc = clip.xy / clip.w;
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return false;
  if (dot(n_hit, gib_frame.camera_pos.xyz - x) <= 0.0) return false;
  ivec2 size = imageSize(prev_position);
  ivec2 q = clamp(ivec2((ndc * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
  vec4 prev = imageLoad(prev_position, q);
  if (prev.w == 0.0) return false;  // sky there last frame
  float depth = (gib_frame.prev_view_proj * vec4(prev.xyz, 1.0)).w;
  if (abs(depth - clip.w) > kGatherScreenDepthTolerance * clip.w) return false;
  radiance = imageLoad(prev_color, q).rgb;
  // Guard: a non-finite pixel of last frame's image is a miss (the world cache answers instead),
  // so a NaN on screen does not feed back into the gather.
  if (rc.flags.y != 0u && !gib_finite(radiance)) return false;
  return true;
}

// One sample's SH for one channel. L1: the Monte Carlo projection L Y1(d) / pdf(d), pdf =
// cos / pi (cos clamped). L0: chosen so the SH's irradiance at the gather normal n is exactly L,
// the cosine-sampled estimate of irradiance / pi there (finite variance; the plain projection
// L Y00 pi / cos has infinite variance). Without the clamp this is L0 = 2 pi Y00 L.
vec4 sample_sh(float radiance, vec4 basis_d, vec4 basis_n, float weight) {
  vec3 l1 = radiance * weight * basis_d.yzw;
  float l0 = (radiance - (2.0 / 3.0) * dot(l1, basis_n.yzw)) / basis_n.x;
  return gib_clamp_keep_nan(vec4(l0, l1), -kHalfMax, kHalfMax);
}

void write_out(ivec2 g, vec4 r, vec4 gg, vec4 b, vec3 direct, float distance) {
  imageStore(out_sh_r, g, r);
  imageStore(out_sh_g, g, gg);
  imageStore(out_sh_b, g, b);
  imageStore(out_direct, g, vec4(direct, 0.0));
  imageStore(out_hit, g, vec4(distance, 0.0, 0.0, 0.0));
}

// Gathers gather pixel g and returns the cache that answered its ray (kGatherStat*), or
// kGatherStatCount when no ray was traced (a sky gather pixel, a broken normal).
uint gather(ivec2 g) {
  int div = int(push.divisor);
  ivec2 full = imageSize(gb_position);
  ivec2 p = min(g * div + div / 2, full - 1);  // the gather pixel's representative
  // The three G-buffer loads are independent: issued together, before any branch, so the face
  // normal's chain (vbuffer -> triangle -> vertices) does not wait for the sky test.
  vec4 pos = imageLoad(gb_position, p);
  vec3 n_raw = imageLoad(gb_normal, p).xyz;
  uint ids = imageLoad(vbuffer, p).x;
  if (pos.w == 0.0) {  // sky: no surface to gather for
    write_out(g, vec4(0.0), vec4(0.0), vec4(0.0), vec3(0.0), 0.0);
    return kGatherStatCount;
  }
  vec3 n = normalize(n_raw);
  if (rc.flags.y != 0u && !gib_finite(n)) {
    // Guard: no direction to gather around (broken G-buffer normal): an empty sample, which
    // gi_denoise and gi_upscale then skip as a tap (its normal is not finite either).
    write_out(g, vec4(0.0), vec4(0.0), vec4(0.0), vec3(0.0), kGatherMissDistance);
    return kGatherStatCount;
  }

  // Ray direction: per pixel, an R2 low-discrepancy sequence over frames (alpha = 1/phi2,
  // 1/phi2^2 in 0.32 fixed point, so it never loses precision), started at a per-pixel hash.
  uint h = gib_pcg(uint(g.x) ^ gib_pcg(uint(g.y) ^ gib_pcg(gib_seed() + 0x52u)));
  uvec2 bits = uvec2(h, gib_pcg(h)) + gib_frame_index() * uvec2(3242174889u, 2447445414u);
  vec2 u = vec2(bits >> 8u) * (1.0 / 16777216.0);
  vec3 d = gib_cosine_hemisphere(n, u);
  float cos_t = sqrt(max(0.0, 1.0 - u.x));
  // Leave as the reference's paths do (surface.glsl gib_above_face): mirrored above the face,
  // offset along the face normal. cos_t (the sample's pdf) is the unmirrored direction's.
  vec3 ng = n;
  if (ids != kVisibilityNone) {
    vec3 o, view;
    gib_camera_ray(vec2(p) + 0.5, o, view);
    ng = gib_face_normal_facing(ids - 1u, view, n);
  }
  d = gib_above_face(d, ng);

  // The ray's radiance in two parts (the AOV contract, renderer/techniques/aov.h): `direct`,
  // what reaches the gather point with no further bounce (the sky where the ray escapes, the
  // emission of the surface it hits), and the rest, light that bounced at the hit.
  vec3 radiance = vec3(0.0), direct = vec3(0.0);
  float distance = kGatherMissDistance;
  uint served = kGatherStatSky;
  GibHit hit;
  if (!trace_closest(gib_offset_ray(pos.xyz, ng), d, 0.0, kFar, hit)) {
    direct = gib_sky_radiance(d);
  } else {
    distance = hit.t;
    GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, rc.flags.y != 0u);
    vec3 n_hit = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;  // the side the ray hit
    // multi_bounce 0: no screen cache (last frame's image holds every bounce so far).
    GpuMaterial m = gib_materials[s.material];
    m.emissive = gib_material_emissive(m, s.uv);  // its emissive texture, if any
    if (push.screen_cache != 0u && rc.flags.z != 0u && screen_cache(s.position, n_hit, radiance)) {
      served = kGatherStatScreen;
    } else if (rc_lookup(s.position, rc_facing_normal(hit.triangle, d), radiance)) {
      served = kGatherStatWorld;
    } else {
      vec3 albedo = gib_material_albedo(m, s.uv);
      radiance = rc_sample_irradiance(s.position, n_hit, -d) * albedo + m.emissive;
      served = kGatherStatVolume;
    }
    // Every source's answer includes the hit's own emission: that part is direct.
    direct = m.emissive;
    radiance = max(radiance - m.emissive, vec3(0.0));
  }
  // Guard: the world cache and the volumes are RGB9E5 (always finite), but a non-finite answer
  // from any source is treated as a miss that returns nothing.
  if (rc.flags.y != 0u && !gib_finite(radiance)) radiance = vec3(0.0);
  if (rc.flags.y != 0u && !gib_finite(direct)) direct = vec3(0.0);
  if (push.sky == 0u) direct = vec3(0.0);  // direct_lighting's own rays count it (sky_rays > 0)
  // Pre-exposure: the SH (RGBA16F) hold radiance x P, P ~ 1 / the frame's typical luminance,
  // so bright skies do not clamp at the format's maximum; gi_upscale divides it out.
  radiance = gib_max0_keep_nan(radiance * exposure[kGatherExposureNow]);
  // The direct part is a cosine-sampled estimate of irradiance / pi at the gather normal.
  direct = gib_clamp_keep_nan(vec4(direct * exposure[kGatherExposureNow], 0.0), 0.0, kHalfMax).rgb;
  float weight = GIB_PI / max(cos_t, kGatherMinCos);
  vec4 bd = gib_sh2_basis(d), bn = gib_sh2_basis(n);
  write_out(g, sample_sh(radiance.r, bd, bn, weight), sample_sh(radiance.g, bd, bn, weight),
            sample_sh(radiance.b, bd, bn, weight), direct, distance);
  return served;
}

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  uint served = all(lessThan(g, imageSize(out_hit))) ? gather(g) : kGatherStatCount;
  // gather_stats: one atomic per subgroup and counter instead of one per pixel on 4 contended
  // addresses. Every invocation reaches this point (no early return in main), so the ballot
  // sees the whole subgroup; the counts are the same whatever the order of the atomics.
  for (uint c = 0u; c < kGatherStatCount; ++c) {
    uint count = subgroupBallotBitCount(subgroupBallot(served == c));
    if (count != 0u && subgroupElect()) atomicAdd(gather_stats[c], count);
  }
}
