// The BRDF classes (Scene BrdfKind). standard: Lambertian, albedo / pi (thin translucency is
// handled where light is gathered: direct_light.glsl, path_trace.comp). cloth: Lambertian plus a
// sheen lobe, sheen x D x V, with the "Charlie" distribution of Estevez and Kulla (2017),
// D = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi), a = max(roughness^2, 0.01), and the visibility term
// of Neubelt and Pettineo (2013), V = 1 / (4 (n.l + n.v - n.l n.v)). Grey sheen (one scalar).
// glossy: a GGX (Trowbridge-Reitz) specular layer over a Lambertian base (below).
// CPU mirror: renderer/scene/material_eval.h (sheen_lobe, glossy_*). Needs GIB_PI and gib_onb,
// gib_luminance (sampling.glsl).
#ifndef GIB_BRDF_GLSL
#define GIB_BRDF_GLSL
#include "sampling.glsl"

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

// ---- glossy class (BrdfKind::glossy) ------------------------------------------------------
// f(wo, wi) = F D V + (1 - metalness) (1 - F) albedo / pi, with
//   a = max(roughness^2, GIB_GGX_MIN_ALPHA), D the GGX distribution (Trowbridge-Reitz),
//   V = G2 / (4 n.l n.v), G2 Smith's height-correlated masking-shadowing (Heitz 2014),
//   F = Schlick's Fresnel, F0 = mix(0.04, albedo, metalness), evaluated at the view angle n.wo.
// F at n.wo (not h.wo) makes the split a layer: the specular layer reflects F times the lobe's
// directional albedo E_ggx(wo) <= 1, the base gets the rest, so the directional albedo
// F E_ggx + (1 - m)(1 - F) albedo <= 1 for any inputs (energy bound by construction). The cost:
// f is not reciprocal (wo is always the camera side here). Single scattering: E_ggx < 1 at high
// roughness (the energy the lobe loses to multiple scattering between microfacets is lost).
const float GIB_GGX_MIN_ALPHA = 0.002;
const uint GIB_BRDF_GLOSSY = 2u;

float gib_ggx_alpha(float roughness) { return max(roughness * roughness, GIB_GGX_MIN_ALPHA); }

// D(h) for cos(theta_h) = nh (1/sr; integrates to 1 against n.h).
float gib_ggx_d(float a, float nh) {
  float a2 = a * a;
  float t = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (GIB_PI * t * t);
}

// G2 / (4 nl nv), height-correlated Smith.
float gib_ggx_v(float a, float nl, float nv) {
  float a2 = a * a;
  float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / (gv + gl);
}

// G1(v): Smith masking of one direction.
float gib_ggx_g1(float a, float nv) {
  float a2 = a * a;
  return 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv));
}

vec3 gib_schlick(vec3 f0, float c) {
  float k = 1.0 - clamp(c, 0.0, 1.0);
  float k2 = k * k;
  return f0 + (vec3(1.0) - f0) * (k2 * k2 * k);
}

vec3 gib_glossy_f0(vec3 albedo, float metalness) { return mix(vec3(0.04), albedo, metalness); }

// The two lobes' values (1/sr, no cosine); 0 where either direction is below the surface.
void gib_glossy_eval(vec3 n, vec3 wo, vec3 wi, vec3 albedo, float roughness, float metalness, out vec3 spec,
                     out vec3 diffuse) {
  spec = vec3(0.0);
  diffuse = vec3(0.0);
  float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0 && nv > 0.0)) return;
  vec3 h = normalize(wi + wo);
  float a = gib_ggx_alpha(roughness);
  vec3 f = gib_schlick(gib_glossy_f0(albedo, metalness), nv);
  spec = f * (gib_ggx_d(a, clamp(dot(n, h), 0.0, 1.0)) * gib_ggx_v(a, nl, nv));
  diffuse = (1.0 - metalness) * (vec3(1.0) - f) * albedo / GIB_PI;
}

// Probability of sampling the specular lobe (else the cosine lobe): the lobes' weights by
// luminance, F against (1 - m)(1 - F) albedo, at n.wo.
float gib_glossy_spec_probability(vec3 n, vec3 wo, vec3 albedo, float metalness) {
  vec3 f = gib_schlick(gib_glossy_f0(albedo, metalness), dot(n, wo));
  float s = gib_luminance(f);
  float d = gib_luminance((1.0 - metalness) * (vec3(1.0) - f) * albedo);
  return s + d > 0.0 ? s / (s + d) : 1.0;
}

// Visible-normal sampling (Heitz 2018): a microfacet normal h seen from wo, in world space, with
// density G1(wo) max(0, wo.h) D(h) / n.wo; wi = reflect(-wo, h) then has pdf G1 D / (4 n.wo).
vec3 gib_ggx_sample_vndf(vec3 n, vec3 wo, float a, vec2 u) {
  vec3 t, b;
  gib_onb(n, t, b);
  vec3 v = vec3(dot(wo, t), dot(wo, b), dot(wo, n));
  vec3 vh = normalize(vec3(a * v.x, a * v.y, v.z));  // the view in the hemisphere configuration
  float l2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = l2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(l2) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x), phi = 2.0 * GIB_PI * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  vec3 hl = normalize(vec3(a * nh.x, a * nh.y, max(0.0, nh.z)));
  return normalize(t * hl.x + b * hl.y + n * hl.z);
}

// Density of wi under the one-sample mixture: p_spec x (VNDF reflected) + (1 - p_spec) x cosine.
float gib_glossy_pdf(vec3 n, vec3 wo, vec3 wi, float roughness, float p_spec) {
  float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0 && nv > 0.0)) return 0.0;
  float a = gib_ggx_alpha(roughness);
  vec3 h = normalize(wi + wo);
  float spec = gib_ggx_g1(a, nv) * gib_ggx_d(a, clamp(dot(n, h), 0.0, 1.0)) / (4.0 * nv);
  return p_spec * spec + (1.0 - p_spec) * nl / GIB_PI;
}

// Sample a direction from the mixture: u.xy the lobe's 2D sample, pick chooses the lobe.
vec3 gib_glossy_sample(vec3 n, vec3 wo, float roughness, float p_spec, vec2 u, float pick) {
  if (pick < p_spec) return reflect(-wo, gib_ggx_sample_vndf(n, wo, gib_ggx_alpha(roughness), u));
  return gib_cosine_hemisphere(n, u);
}

#endif
