// irradiance_volume_update: the steps its two kernel layouts share (irradiance_volume_probe.comp
// on GPUs, irradiance_volume_rays.comp + irradiance_volume_update.comp on CPU devices). Include
// after the push constants `rc`, probe_volume.glsl with RC_PROBE_IMAGES, radiance_cache.glsl with
// RC_CELL_BUFFER (ray shading only: define IV_SHADE_RAYS), surface.glsl and finite.glsl; the
// including shader declares the spec constant kCacheFallback when it shades rays.
#ifndef GIB_IRRADIANCE_VOLUME_COMMON_GLSL
#define GIB_IRRADIANCE_VOLUME_COMMON_GLSL

#include "hash.glsl"
const float kIvInsideMark = -2.0;  // probe_ray_radiance.w of a ray inside geometry (-1: dropped)
layout(constant_id = kIvSpecDither) const bool kIvDither = false;

// The irradiance texel's RGB9E5 store: rounded to nearest, or (kIvDither, option dither_stores)
// stochastically, with a dither drawn from the interior texel `at` and the frame, so a border
// texel and the interior texel it mirrors store the same bits. Blended at hysteresis h, a texel
// moves by (1 - h) x (new - last) per update; rounded to nearest it stops once that is below
// half a unit (about 0.1% of the value), which holds a slowly converging probe (the multi-bounce
// feedback of a closed room) short of its limit. Dithered, its expectation keeps moving.
uint iv_pack_irradiance(ivec2 at, vec3 irradiance) {
  if (!kIvDither) return gib_pack_rgb9e5(irradiance);
  uint dither = gib_pcg(uint(at.x) ^ gib_pcg(uint(at.y) ^ gib_pcg(rc.misc.x ^ 0x632be5abu)));
  return gib_pack_rgb9e5_dither(irradiance, dither);
}

#ifdef IV_SHADE_RAYS
// Radiance arriving at the probe along ray d that hit h at p (its cell was not found).
vec3 iv_fallback_radiance(ProbeHit h, vec3 p, vec3 d) {
  if (!kCacheFallback) return vec3(0.0);
  vec2 bary = vec2(h.barycentrics & 0xffffu, h.barycentrics >> 16u) * (1.0 / 65535.0);
  GibSurface s = gib_surface(h.triangle_plus1 - 1u, bary.x, bary.y, rc.flags.y != 0u);
  GpuMaterial m = gib_materials[s.material];
  if (rc.flags.z == 0u) return gib_material_emissive(m, s.uv);  // single bounce: the volumes hold bounced light
  vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  return gib_material_emissive(m, s.uv) + gib_material_albedo(m, s.uv) * rc_sample_irradiance(p, n, -d);
}

// What a probe ray brings: light, nothing (dropped by the NaN guard), or nothing because it hit
// from inside geometry (rc_probe_ray_inside), which also counts towards the probe being inside;
// kIvRayMissed: its hit has no shaded cell and the fallback is left to another dispatch (the
// including shader defines IV_DEFER_FALLBACK true for that).
const uint kIvRayLit = 0u, kIvRayDropped = 1u, kIvRayInside = 2u, kIvRayMissed = 3u;
#ifndef IV_DEFER_FALLBACK
#define IV_DEFER_FALLBACK false
#endif

// The radiance arriving at probe position o of cascade c along ray direction d with hit record
// h: sky on a miss, the cache cell at the hit, else the fallback; l is 0 unless kIvRayLit.
uint iv_ray_radiance(ProbeHit h, vec3 o, vec3 d, uint c, out vec3 l) {
  l = vec3(0.0);
  if (h.triangle_plus1 == 0u) {
    l = gib_sky_radiance(d);
  } else if (h.key == 0u) {
    return kIvRayInside;  // probe_trace found the ray inside geometry (rc_probe_ray_inside)
  } else if (!rc_lookup_key(h.key, l)) {
    if (IV_DEFER_FALLBACK) {
      l = vec3(0.0);
      return kIvRayMissed;
    }
    l = iv_fallback_radiance(h, rc_hit_position(o, d, h.distance), d);
  }
  if (rc.flags.y == 0u || gib_finite(l)) return kIvRayLit;
  l = vec3(0.0);
  return kIvRayDropped;
}
#endif

// Last frame's texel of the atlas: its RGB9E5 irradiance and its moments. Loaded by
// iv_load_last_frame before the texel's convolution, so the two loads' latency hides behind it
// (loaded after it, one after the other as the blend needed them, they were waited for in turn).
struct IvLastFrame {
  uint irradiance;
  vec2 moments;
};
IvLastFrame iv_load_last_frame(ivec2 at) { return IvLastFrame(rc_probe_irradiance_texel(at), rc_probe_visibility_texel(at)); }

// Blends a texel's new irradiance and moments with last frame's (hysteresis), then floors the
// mean distance: a written probe never has a zero mean distance, which marks "never updated".
void iv_blend_with_last_frame(IvLastFrame last, inout vec3 irradiance, inout vec2 moments) {
  vec2 prev_moments = last.moments;
  // Guard: a non-finite previous texel is not blended (the probe restarts as on its first
  // update). The irradiance texel is RGB9E5, which cannot hold a NaN; the moments are RG16F.
  bool prev_ok = rc.flags.y == 0u || gib_finite(prev_moments);
  if (prev_ok && prev_moments.x > 0.0) {
    float hysteresis = clamp(rc.bias.w, 0.0, 1.0);
    irradiance = mix(irradiance, gib_unpack_rgb9e5(last.irradiance), hysteresis);
    moments = mix(moments, prev_moments, hysteresis);
  }
  moments.x = max(moments.x, 1e-3);
}

// A probe with more than kRcInsideFraction of this update's rays inside geometry
// (rc_probe_ray_inside) is inside: its texels store irradiance 0 and moments 0, as a probe never
// updated, which every sampler skips (rc_sample_irradiance_weight: m.x <= 0) and which restarts
// without history once an update finds it outside. (Not a negative marker: the stability scan
// holds the moments to [0, max distance].) Else the texel is blended with last frame's.
void iv_finish_texel(IvLastFrame last, uint inside_rays, uint rays, inout vec3 irradiance, inout vec2 moments) {
  if (float(inside_rays) > kRcInsideFraction * float(rays)) {
    irradiance = vec3(0.0);
    moments = vec2(0.0);
    return;
  }
  iv_blend_with_last_frame(last, irradiance, moments);
}

#endif
