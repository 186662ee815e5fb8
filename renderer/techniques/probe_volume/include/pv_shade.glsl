// Lighting of a secondary hit, shared by probe_relight (probe texels) and hit_lighting (per-pixel
// rays): AC Shadows "Lighting update: Hit" and "Secondary hit" (thin translucency: direct light
// on both faces, irradiance on both normals). Lambertian: albedo x (1 - t) reflects light on
// the front, albedo x t transmits light from the back (t: translucency), as direct_light.glsl.
// Needs: scene buffers, frame.glsl, lights.glsl, surface.glsl, bvh (trace_any), pv_sample.glsl;
// the includer defines kHasLocal (bool).
#ifndef GIB_PV_SHADE_GLSL
#define GIB_PV_SHADE_GLSL

// Reflected radiance (x pi / albedo) from the sun, given its visibility on the side it reaches.
vec3 pv_sun(vec3 n, float translucency, float visibility) {
  if (gib_frame.sun_irradiance.w <= 0.0) return vec3(0.0);
  return gib_thin_facing(translucency, n, gib_frame.sun_dir.xyz) * visibility * gib_frame.sun_irradiance.rgb;
}

// Reflected radiance (x pi / albedo) from every local light, one shadow ray each.
vec3 pv_local_lights(vec3 x, vec3 n, float translucency) {
  vec3 sum = vec3(0.0);
  if (!kHasLocal) return sum;
  for (uint i = 0u; i < gib_light_count(); ++i) {
    vec3 wi;
    float dist;
    vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
    float w = gib_thin_facing(translucency, n, wi);
    if (w <= 0.0 || all(equal(e, vec3(0.0)))) continue;
    if (!trace_any(gib_offset_ray(x, dot(n, wi) > 0.0 ? n : -n), wi, 0.0, dist * 0.999)) sum += w * e;
  }
  return sum;
}

// Irradiance / pi from the probes on the seen side (and, for a translucent surface, the back
// side's share): (1 - t) E(n) + t E(-n), each side with the probes of its own class.
// d: the incoming ray (unit), length its hit distance.
vec3 pv_bounce(vec3 x, vec3 n, float translucency, vec3 d, float length) {
  vec3 e = (1.0 - translucency) * pv_sample_irradiance(x, n, -d, d, length, pv_point_indoor(x, n));
  if (translucency > 0.0) e += translucency * pv_sample_irradiance(x, -n, -d, d, length, pv_point_indoor(x, -n));
  return e;
}

#endif  // GIB_PV_SHADE_GLSL
