// The BRDF classes (Scene BrdfKind). standard: Lambertian, albedo / pi (thin translucency is
// handled where light is gathered: direct_light.glsl, path_trace.comp). cloth: Lambertian plus a
// sheen lobe, sheen x D x V, with the "Charlie" distribution of Estevez and Kulla (2017),
// D = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi), a = max(roughness^2, 0.01), and the visibility term
// of Neubelt and Pettineo (2013), V = 1 / (4 (n.l + n.v - n.l n.v)). Grey sheen (one scalar).
// CPU mirror: renderer/scene/material_eval.h (sheen_lobe). Needs GIB_PI (sampling.glsl).
#ifndef GIB_BRDF_GLSL
#define GIB_BRDF_GLSL

// sheen x D x V (1/sr) for light from wi seen from wo; 0 where either is below the surface.
float gib_sheen_lobe(float sheen, float roughness, vec3 n, vec3 wi, vec3 wo) {
  float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0 && nv > 0.0)) return 0.0;
  vec3 h = normalize(wi + wo);
  float nh = clamp(dot(n, h), 0.0, 1.0);
  float a = max(roughness * roughness, 0.01);
  float inv_a = 1.0 / a;
  float sin2 = max(1.0 - nh * nh, 0.0);
  float d = (2.0 + inv_a) * pow(sin2, 0.5 * inv_a) / (2.0 * GIB_PI);
  float v = 1.0 / (4.0 * (nl + nv - nl * nv));
  return sheen * d * v;
}

#endif
