// Two-band spherical harmonics (owner: codecs). CPU mirror and the full description:
// renderer/codecs/sh2.h.
// Order (vec4 x, y, z, w) = (Y00, Y1-1, Y10, Y11) = (0.282095, 0.488603 d.y, 0.488603 d.z,
// 0.488603 d.x). Coefficients are projections of radiance: c = sum of L(d_i) basis(d_i) w_i with
// w_i the sample's solid angle (4 pi / N for N uniform directions).
//   vec4 gib_sh2_basis(vec3 d)
//   vec4 gib_sh2_project(vec3 d, float value)   value * gib_sh2_basis(d)
//   float gib_sh2_eval(vec4 sh, vec3 d)          reconstructed signal in direction d
//   float gib_sh2_irradiance(vec4 sh, vec3 n)    IRRADIANCE / PI (cosine lobe, A0 = pi,
//       A1 = 2pi/3): constant radiance L -> L; the outgoing radiance of a white Lambertian
//       surface, so multiply by albedo, not by albedo / pi.
#ifndef GIB_SH_GLSL
#define GIB_SH_GLSL

const float GIB_SH_Y0 = 0.282095;
const float GIB_SH_Y1 = 0.488603;

vec4 gib_sh2_basis(vec3 d) { return vec4(GIB_SH_Y0, GIB_SH_Y1 * d.y, GIB_SH_Y1 * d.z, GIB_SH_Y1 * d.x); }

vec4 gib_sh2_project(vec3 d, float value) { return gib_sh2_basis(d) * value; }

float gib_sh2_eval(vec4 sh, vec3 d) { return dot(sh, gib_sh2_basis(d)); }

float gib_sh2_irradiance(vec4 sh, vec3 n) {
  vec4 b = gib_sh2_basis(n);
  return sh.x * b.x + (2.0 / 3.0) * (sh.y * b.y + sh.z * b.z + sh.w * b.w);
}

#endif  // GIB_SH_GLSL
