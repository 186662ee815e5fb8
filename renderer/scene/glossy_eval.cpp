// CPU mirror of brdf.glsl's glossy class (declared in material_eval.h): the same formulas in the
// same operation order as gib_ggx_* and gib_glossy_*, so tests can compare the two on the device.
#include <algorithm>
#include <cmath>

#include "renderer/scene/material_eval.h"

namespace gib {
namespace {
constexpr float kPi = 3.14159265358979f;
float luminance(Vec3 c) { return c.x * 0.2126f + c.y * 0.7152f + c.z * 0.0722f; }
Vec3 reflect(Vec3 i, Vec3 n) { return i - n * (2.0f * dot(n, i)); }
Vec3 f0_of(Vec3 albedo, float m) { return Vec3{0.04f, 0.04f, 0.04f} * (1.0f - m) + albedo * m; }
// gib_onb (sampling.glsl), Duff et al. 2017.
void onb(Vec3 n, Vec3& t, Vec3& b) {
  const float s = n.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (s + n.z);
  const float c = n.x * n.y * a;
  t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
  b = {c, s + n.y * n.y * a, -n.y};
}
}  // namespace

float ggx_alpha(float roughness) { return std::fmax(roughness * roughness, kGgxMinAlpha); }

float ggx_d(float a, float nh) {
  const float a2 = a * a;
  const float t = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * t * t);
}

float ggx_v(float a, float nl, float nv) {
  const float a2 = a * a;
  const float gv = nl * std::sqrt(nv * nv * (1.0f - a2) + a2);
  const float gl = nv * std::sqrt(nl * nl * (1.0f - a2) + a2);
  return 0.5f / (gv + gl);
}

float ggx_g1(float a, float nv) {
  const float a2 = a * a;
  return 2.0f * nv / (nv + std::sqrt(a2 + (1.0f - a2) * nv * nv));
}

Vec3 schlick(Vec3 f0, float c) {
  const float k = 1.0f - std::clamp(c, 0.0f, 1.0f);
  const float k2 = k * k;
  const float k5 = k2 * k2 * k;
  return {f0.x + (1.0f - f0.x) * k5, f0.y + (1.0f - f0.y) * k5, f0.z + (1.0f - f0.z) * k5};
}

GlossyLobes glossy_eval(Vec3 n, Vec3 wo, Vec3 wi, Vec3 albedo, float roughness, float metalness) {
  GlossyLobes r;
  const float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0f && nv > 0.0f)) return r;
  const Vec3 h = normalize(wi + wo);
  const float a = ggx_alpha(roughness);
  const Vec3 f = schlick(f0_of(albedo, metalness), nv);
  r.spec = f * (ggx_d(a, std::clamp(dot(n, h), 0.0f, 1.0f)) * ggx_v(a, nl, nv));
  r.diffuse = (Vec3{1, 1, 1} - f) * (1.0f - metalness) * albedo / kPi;
  return r;
}

float glossy_spec_probability(Vec3 n, Vec3 wo, Vec3 albedo, float metalness) {
  const Vec3 f = schlick(f0_of(albedo, metalness), dot(n, wo));
  const float s = luminance(f);
  const float d = luminance((Vec3{1, 1, 1} - f) * (1.0f - metalness) * albedo);
  return s + d > 0.0f ? s / (s + d) : 1.0f;
}

Vec3 ggx_sample_vndf(Vec3 n, Vec3 wo, float a, float u0, float u1) {
  Vec3 t, b;
  onb(n, t, b);
  const Vec3 v{dot(wo, t), dot(wo, b), dot(wo, n)};
  const Vec3 vh = normalize({a * v.x, a * v.y, v.z});
  const float l2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = l2 > 0.0f ? Vec3{-vh.y, vh.x, 0.0f} * (1.0f / std::sqrt(l2)) : Vec3{1, 0, 0};
  const Vec3 t2 = cross(vh, t1);
  const float r = std::sqrt(u0), phi = 2.0f * kPi * u1;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1 - p2 * p2));
  const Vec3 hl = normalize({a * nh.x, a * nh.y, std::fmax(0.0f, nh.z)});
  return normalize(t * hl.x + b * hl.y + n * hl.z);
}

float glossy_pdf(Vec3 n, Vec3 wo, Vec3 wi, float roughness, float p_spec) {
  const float nl = dot(n, wi), nv = dot(n, wo);
  if (!(nl > 0.0f && nv > 0.0f)) return 0.0f;
  const float a = ggx_alpha(roughness);
  const Vec3 h = normalize(wi + wo);
  const float spec = ggx_g1(a, nv) * ggx_d(a, std::clamp(dot(n, h), 0.0f, 1.0f)) / (4.0f * nv);
  return p_spec * spec + (1.0f - p_spec) * nl / kPi;
}

Vec3 glossy_sample(Vec3 n, Vec3 wo, float roughness, float p_spec, float u0, float u1, float pick) {
  if (pick < p_spec) return reflect(-wo, ggx_sample_vndf(n, wo, ggx_alpha(roughness), u0, u1));
  // gib_cosine_hemisphere
  const float r = std::sqrt(u0), phi = 2.0f * kPi * u1;
  Vec3 t, b;
  onb(n, t, b);
  return normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::fmax(0.0f, 1.0f - u0)));
}

double ggx_directional_albedo(float roughness, float cos_view, int steps) {
  const double a = ggx_alpha(roughness), a2 = a * a;
  const double nv = cos_view, sv = std::sqrt(std::fmax(0.0, 1.0 - nv * nv));
  const double dt = 3.14159265358979323846 / 2 / steps, dp = 3.14159265358979323846 / steps;
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double th = (i + 0.5) * dt, nl = std::cos(th), sl = std::sin(th);
    for (int j = 0; j < 2 * steps; ++j) {
      const double ph = (j + 0.5) * dp;
      // h = normalize(wi + wo), wo = (sv, 0, nv), wi = (sl cos ph, sl sin ph, nl)
      const double hx = sl * std::cos(ph) + sv, hy = sl * std::sin(ph), hz = nl + nv;
      const double nh = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
      const double t = nh * nh * (a2 - 1) + 1;
      const double d = a2 / (3.14159265358979323846 * t * t);
      const double v = 0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
      sum += d * v * nl * sl;
    }
  }
  return sum * dt * dp;
}

}  // namespace gib
