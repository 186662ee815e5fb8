// Probe sampling (AC Shadows "Light leaks: probe filtering" and "Lighting on miss"): the 8
// probes around a point of the finest cascade that surrounds it, weighted by
//   1. a wrap-shading directional weight ((dot(to probe, n) + 1) / 2)^2 (irradiance only),
//   2. Chebyshev's bound on the probe's depth moments (visibility_test),
//   3. weights under 0.2 crushed (w *= w^2 / 0.2^2),
//   4. the trilinear weight,
// after moving the point along the normal and towards the viewer (normal_offset, view_offset,
// in cascade spacings) and back along the incoming ray, by at most half its length
// (inverse_ray_offset, the DDGI-resampling offset). Probes not valid, disabled, or of the other
// indoor/outdoor class than the point skip. When the nearest probe's trilinear weight exceeds
// pv.sampling.z it alone is fetched (the seed's nearest-probe fast path). A cascade whose 8
// probes all skip passes to the next coarser one.
//
// Use: after pv_common.glsl, PV_STATE_BUFFER(...) and PV_PROBE_BUFFERS(...) (pv_common.glsl):
//   vec3 e_over_pi = pv_sample_irradiance(x, n, to_viewer, incoming, ray_length, indoor);
//   vec4 rad = pv_sample_radiance(x, d, indoor);   // rgb reflected radiance, a sky visibility
//   bool inside = pv_cascade_at(x) < kPvMaxCascades;
#ifndef GIB_PV_SAMPLE_GLSL
#define GIB_PV_SAMPLE_GLSL
#include "renderer/techniques/probe_volume/include/pv_volume.glsl"

const float kPvCrush = 0.2;

vec4 pv_half4(uvec2 w) { return vec4(gib_unpack_half2x16(w.x), gib_unpack_half2x16(w.y)); }

// Bilinear fetch from a bordered octahedral tile (side = interior + 2) of direction d.
vec4 pv_irradiance_texel(uint probe, ivec2 t) { return pv_half4(pv_irradiance[pv_irradiance_index(probe, t)]); }
vec4 pv_radiance_texel(uint probe, ivec2 t) { return pv_half4(pv_radiance[pv_radiance_index(probe, t)]); }
vec2 pv_visibility_texel(uint probe, ivec2 t) {
  uint k = uint(t.y) * kPvRadianceSide + uint(t.x);
  uint w = pv_visibility[(probe * kPvRadianceTexels + k) >> 1u] >> ((k & 1u) * 16u);
  return vec2(w & 255u, (w >> 8u) & 255u) * (1.0 / 255.0);
}
#define PV_BILINEAR(FETCH, TYPE, probe, d, interior)                                  \
  {                                                                                    \
    vec2 tc = gib_oct_tile_coord(d, int(interior)) - 0.5;                              \
    ivec2 i0 = ivec2(floor(tc));                                                        \
    vec2 f = tc - vec2(i0);                                                             \
    TYPE a = FETCH(probe, i0), b = FETCH(probe, i0 + ivec2(1, 0));                      \
    TYPE c = FETCH(probe, i0 + ivec2(0, 1)), e = FETCH(probe, i0 + ivec2(1, 1));        \
    return mix(mix(a, b, f.x), mix(c, e, f.x), f.y);                                    \
  }
vec4 pv_irradiance_at(uint probe, vec3 d) PV_BILINEAR(pv_irradiance_texel, vec4, probe, d, kPvIrradianceInterior)
vec4 pv_radiance_at(uint probe, vec3 d) PV_BILINEAR(pv_radiance_texel, vec4, probe, d, kPvRadianceInterior)
vec2 pv_visibility_at(uint probe, vec3 d) PV_BILINEAR(pv_visibility_texel, vec2, probe, d, kPvRadianceInterior)

bool pv_probe_usable(PvProbe p, ivec3 cell, bool indoor) {
  uint f = uint(p.coord.w);
  return (f & kPvProbeValid) != 0u && (f & kPvProbeDisabled) == 0u && all(equal(p.coord.xyz, cell)) &&
         (((f & kPvProbeIndoor) != 0u) == indoor);
}

// Chebyshev's upper bound on the chance that the probe sees a point at distance `dist`
// (metres) in direction d from it, from its depth moments (unit: spacing * sqrt(3)).
float pv_chebyshev(uint probe, vec3 d, float dist, float spacing) {
  vec2 m = pv_visibility_at(probe, d);
  float z = min(dist / (spacing * kPvSqrt3), 1.0);
  if (z <= m.x) return 1.0;
  float variance = max(m.y - m.x * m.x, 1.0 / 65025.0);
  float t = z - m.x;
  return variance / (variance + t * t);
}

// Weighted sum over the 8 probes of cascade c around p (or the nearest alone): rgb/a value of
// `fetch` (0 irradiance for normal n, 1 radiance for direction n), divided by each probe's
// lighting scale; w: the weight sum (0: no usable probe).
vec4 pv_gather(uint c, vec3 p, vec3 n, bool radiance, bool indoor, out float weight_sum) {
  float s = pv_spacing(c);
  vec3 g = p / s - 0.5;
  ivec3 base = ivec3(floor(g));
  vec3 f = g - vec3(base);
  vec4 sum = vec4(0.0);
  weight_sum = 0.0;
  // Nearest-probe fast path.
  ivec3 near = ivec3(greaterThanEqual(f, vec3(0.5)));
  vec3 tn = mix(1.0 - f, f, vec3(near));
  bool fast = tn.x * tn.y * tn.z > pv.sampling.z;
  for (uint i = 0u; i < 8u; ++i) {
    ivec3 corner = ivec3(i & 1u, (i >> 1u) & 1u, i >> 2u);
    if (fast && any(notEqual(corner, near))) continue;
    ivec3 cell = base + corner;
    uint probe = pv_probe_index(c, cell);
    PvProbe pr = pv_probes[probe];
    if (!pv_probe_usable(pr, cell, indoor)) continue;
    vec3 t3 = mix(1.0 - f, f, vec3(corner));
    float trilinear = fast ? 1.0 : t3.x * t3.y * t3.z;
    vec3 to_probe = pv_cell_position(c, cell) + pr.offset.xyz - p;
    float dist = length(to_probe);
    vec3 dir = dist > 0.0 ? to_probe / dist : n;
    float w = 1.0;
    if (!radiance) {
      float wrap = (dot(dir, n) + 1.0) * 0.5;
      w = wrap * wrap;
    }
    if (pv_flag(kPvFlagVisibility)) w *= pv_chebyshev(probe, -dir, dist, s);
    if (w < kPvCrush) w *= w * w * (1.0 / (kPvCrush * kPvCrush));
    w *= trilinear;
    if (w <= 0.0) continue;
    vec4 v = radiance ? pv_radiance_at(probe, n) : pv_irradiance_at(probe, n);
    float scale = max(pr.offset.w, 1e-30);
    sum += w * vec4(v.rgb / scale, v.a);
    weight_sum += w;
  }
  return weight_sum > 0.0 ? sum / weight_sum : vec4(0.0);
}

vec4 pv_gather_cascades(uint c0, vec3 p, vec3 n, bool radiance, bool indoor) {
  for (uint c = c0; c < pv_cascades(); ++c) {
    float w;
    vec4 v = pv_gather(c, p, n, radiance, indoor, w);
    if (w > 0.0) return v;
  }
  return vec4(0.0);
}

// Irradiance / pi at x with normal n (true scale). to_viewer: unit direction towards whoever
// looks at x (the camera, or the origin of the ray that hit x); incoming: unit direction of that
// ray (x = origin + incoming * ray_length). Outside every cascade: 0.
vec3 pv_sample_irradiance(vec3 x, vec3 n, vec3 to_viewer, vec3 incoming, float ray_length, bool indoor) {
  uint c = pv_cascade_at(x);
  if (c >= kPvMaxCascades) return vec3(0.0);
  float s = pv_spacing(c);
  vec3 p = x + n * (pv.sampling.x * s) + to_viewer * (pv.sampling.y * s);
  if (pv_flag(kPvFlagInverseRay)) p -= incoming * min(pv.sampling.x * s, 0.5 * ray_length);
  return pv_gather_cascades(c, p, n, false, indoor).rgb;
}

// Filtered radiance arriving at x from direction -d (travelling along d): rgb reflected
// radiance (true scale), a: sky visibility (the sky itself is left to the caller).
vec4 pv_sample_radiance(vec3 x, vec3 d, bool indoor) {
  uint c = pv_cascade_at(x);
  if (c >= kPvMaxCascades) return vec4(0.0, 0.0, 0.0, 1.0);
  return pv_gather_cascades(c, x, d, true, indoor);
}

#endif  // GIB_PV_SAMPLE_GLSL
