// irradiance_volume_update on GPUs: one 8x8 workgroup per probe of the updated cascade; the
// probe's rays are shaded once into group-shared memory, each thread convolves one interior
// texel, then the 10x10 tile with its border is written. CPU devices (lavapipe) use the
// barrier-free pair irradiance_volume_rays.comp + irradiance_volume_update.comp instead (same
// output): there each barrier costs ~70 us per workgroup, while on an H100 the split pair is
// 39% slower (0.108 vs 0.078 ms at ultra).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/irradiance_volume_update/irradiance_volume_update_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "material.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"
layout(constant_id = kIvSpecCacheFallback) const bool kCacheFallback = true;

layout(local_size_x = kIvGroup, local_size_y = kIvGroup) in;
layout(std430, set = 0, binding = kIvBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(set = 0, binding = kIvBindIrradiance, r32ui) uniform writeonly uimage2D out_irradiance;
layout(set = 0, binding = kIvBindVisibility, rg16f) uniform writeonly image2D out_visibility;
layout(push_constant) uniform Push { RcParams rc; };
#include "probe_volume.glsl"
RC_PROBE_IMAGES(kIvBindPrevIrradiance, kIvBindPrevVisibility)
#include "radiance_cache.glsl"
RC_CELL_BUFFER(kIvBindCells, readonly)

const uint kTexels = kProbeTileInterior * kProbeTileInterior;
shared vec3 s_dir[kIvMaxRays];
shared vec3 s_radiance[kIvMaxRays];
shared float s_distance[kIvMaxRays];
shared uint s_irradiance[kTexels];
shared vec2 s_moments[kTexels];

// Radiance arriving at the probe along ray d that hit h at p (its cell was not found).
vec3 fallback_radiance(ProbeHit h, vec3 p, vec3 d) {
  if (!kCacheFallback) return vec3(0.0);
  vec2 bary = vec2(h.barycentrics & 0xffffu, h.barycentrics >> 16u) * (1.0 / 65535.0);
  GibSurface s = gib_surface(h.triangle_plus1 - 1u, bary.x, bary.y, rc.flags.y != 0u);
  GpuMaterial m = gib_materials[s.material];
  if (rc.flags.z == 0u) return m.emissive;  // single bounce: the volumes hold bounced light
  vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  return m.emissive + gib_material_albedo(m, s.uv) * rc_sample_irradiance(p, n, -d);
}

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
    if (h.triangle_plus1 == 0u) {
      l = gib_sky_radiance(d);
    } else {
      vec3 p = rc_hit_position(o, d, h.distance);
      if (!rc_lookup(p, rc_facing_normal(h.triangle_plus1 - 1u, d), l)) l = fallback_radiance(h, p, d);
    }
    // Guard: a non-finite ray is dropped (a zero direction gives it weight 0 in every texel).
    bool drop = rc.flags.y != 0u && !gib_finite(l);
    s_dir[r] = drop ? vec3(0.0) : d;
    s_radiance[r] = drop ? vec3(0.0) : l;
    s_distance[r] = min(h.distance, max_distance);
  }
  barrier();

  ivec2 texel = ivec2(gl_LocalInvocationID.xy);
  vec3 n = gib_oct_texel_direction(texel + 1, int(kProbeTileInterior));
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  vec2 moments = vec2(0.0);
  float moment_weight = 0.0;
  for (uint r = 0u; r < rays; ++r) {
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
  vec2 prev_moments = rc_probe_visibility_texel(at);
  // Guard: a non-finite previous texel is not blended (the probe restarts as on its first
  // update). The irradiance texel is RGB9E5, which cannot hold a NaN; the moments are RG16F.
  bool prev_ok = rc.flags.y == 0u || gib_finite(prev_moments);
  if (prev_ok && prev_moments.x > 0.0) {
    float hysteresis = clamp(rc.bias.w, 0.0, 1.0);
    irradiance = mix(irradiance, gib_unpack_rgb9e5(rc_probe_irradiance_texel(at)), hysteresis);
    moments = mix(moments, prev_moments, hysteresis);
  }
  // A written probe never has a zero mean distance: that marks "never updated".
  moments.x = max(moments.x, 1e-3);
  s_irradiance[tid] = gib_pack_rgb9e5(irradiance);
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
