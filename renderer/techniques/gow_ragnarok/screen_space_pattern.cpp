#include "renderer/techniques/gow_ragnarok/screen_space_pattern.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "renderer/codecs/octahedral.h"

namespace gib {
namespace {

uint32_t pcg(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float next(uint32_t& state) {
  state = state * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8) * (1.0f / 16777216.0f);
}

}  // namespace

SsRotation ss_rotation(uint32_t seed, uint32_t frame, uint32_t px, uint32_t py, uint32_t stream) {
  uint32_t state = pcg(seed ^ pcg(frame ^ pcg(px ^ pcg(py ^ pcg(stream)))));
  const float turn = next(state);
  return {turn, next(state)};
}

Vec3 ss_direction(uint32_t i, uint32_t n, float turn, Vec3 normal) {
  constexpr float kPi = 3.14159265358979f;
  constexpr float kGoldenAngle = 2.39996322972865332f;
  const float u = (float(i) + 0.5f) / float(n);
  const float r = std::sqrt(u);
  const float phi = float(i) * kGoldenAngle + 2.0f * kPi * turn;
  // Orthonormal basis around the normal (Duff et al. 2017), as sampling.glsl's gib_onb.
  const float s = normal.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (s + normal.z);
  const float c = normal.x * normal.y * a;
  const Vec3 t{1.0f + s * normal.x * normal.x * a, s * c, -s * normal.x};
  const Vec3 b{c, s + normal.y * normal.y * a, -normal.y};
  const float h = std::sqrt(std::max(0.0f, 1.0f - u));
  const Vec3 d{t.x * (r * std::cos(phi)) + b.x * (r * std::sin(phi)) + normal.x * h,
               t.y * (r * std::cos(phi)) + b.y * (r * std::sin(phi)) + normal.y * h,
               t.z * (r * std::cos(phi)) + b.z * (r * std::sin(phi)) + normal.z * h};
  const float len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return {d.x / len, d.y / len, d.z / len};
}

void ss_pack_surface(float dist, Vec3 n, uint32_t pixel, uint32_t out[2]) {
  const bool plane = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && dot(n, n) > 0.25f;
  const Vec2 uv = codecs::oct_encode(plane ? n : Vec3{0, 0, 1});
  auto q = [](float v) { return uint32_t(std::floor(std::clamp(v, 0.0f, 1.0f) * 32767.0f + 0.5f)); };
  out[0] = std::bit_cast<uint32_t>(std::fabs(dist)) | (plane ? 0u : 0x80000000u);
  out[1] = (pixel & 3u) | (q(uv.x) << 2u) | (q(uv.y) << 17u);
}

SsSurface ss_unpack_surface(const uint32_t in[2]) {
  SsSurface s;
  s.dist = std::bit_cast<float>(in[0] & 0x7fffffffu);
  s.plane = (in[0] & 0x80000000u) == 0u;
  s.normal = codecs::oct_decode({float((in[1] >> 2u) & 0x7fffu) / 32767.0f, float(in[1] >> 17u) / 32767.0f});
  s.pixel = in[1] & 3u;
  return s;
}

}  // namespace gib
