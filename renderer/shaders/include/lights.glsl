// Sky radiance and local-light evaluation shared by every pass that lights a point.
// Requires frame.glsl and scene.glsl (for GpuLight).
#ifndef GIB_LIGHTS_GLSL
#define GIB_LIGHTS_GLSL
#include "sampling.glsl"

// SkyKind: 0 none, 1 constant, 2 gradient, 3 analytic. The sun disk itself is never part of
// the sky: it is lit only by next-event estimation, so no path counts it twice.
vec3 gib_sky_radiance(vec3 d) {
  uint kind = uint(gib_frame.sky_zenith.w);
  vec3 zenith = gib_frame.sky_zenith.rgb;
  if (kind == 0u) return vec3(0.0);
  if (kind == 1u) return zenith;
  vec3 horizon = gib_frame.sky_horizon.rgb, ground = gib_frame.sky_ground.rgb;
  if (d.y < 0.0) return ground;
  if (kind == 2u) return mix(horizon, zenith, sqrt(clamp(d.y, 0.0, 1.0)));
  // analytic: zenith/horizon blend plus a turbidity-dependent glow around the sun (a cheap
  // Preetham-like shape, not a fitted model).
  float t = gib_frame.sky_horizon.w;
  vec3 base = mix(horizon, zenith, pow(clamp(d.y, 0.0, 1.0), 0.4));
  float mu = max(dot(d, gib_frame.sun_dir.xyz), 0.0);
  float glow = 0.05 * t * pow(mu, 8.0) * gib_frame.sun_irradiance.w;
  return base * (1.0 + glow);
}

// Lambertian weight (times pi) of light from wi at a thin surface whose seen side has normal n:
// reflected on the front, transmitted from the back scaled by translucency. Multiplied by an
// irradiance-like e and albedo / pi by the caller.
float gib_thin_facing(float translucency, vec3 n, vec3 wi) {
  float c = dot(n, wi);
  return c > 0.0 ? (1.0 - translucency) * c : translucency * (-c);
}

// Radiance arriving at p from local light l (before visibility), and the direction/distance
// to it. Inverse-square falloff, spot smoothstep between outer and inner cones, zero past range.
vec3 gib_local_light(GpuLight l, vec3 p, out vec3 wi, out float dist) {
  vec3 d = l.position - p;
  float d2 = max(dot(d, d), 1e-8);
  dist = sqrt(d2);
  wi = d / dist;
  if (dist > l.range) return vec3(0.0);
  vec3 e = l.intensity / d2;
  if (l.kind == 1u) {
    float c = dot(-wi, l.direction);
    e *= smoothstep(l.cos_outer, l.cos_inner, c);
  }
  return e;
}
#endif
