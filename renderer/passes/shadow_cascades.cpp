// Mirrors of shadow_cascades.glsl, line for line, in float (the GPU's precision).
#include "renderer/passes/shadow_cascades.h"

#include <algorithm>
#include <cmath>

namespace gib {

uint32_t shadow_map_resolution(const SunShadowParams& s) {
  const uint32_t t = glsl::kShadowMinMaxTile;
  return std::max<uint32_t>(8 * t, (s.shadow_resolution + t - 1) / t * t);
}

std::vector<float> cascade_splits(uint32_t n, float near_plane, float far_plane, float lambda) {
  std::vector<float> out(n);
  for (uint32_t i = 1; i <= n; ++i) {
    const double f = double(i) / n;
    const double log_split = double(near_plane) * std::pow(double(far_plane) / near_plane, f);
    const double uniform = near_plane + (double(far_plane) - near_plane) * f;
    out[i - 1] = float(lambda * log_split + (1.0 - lambda) * uniform);
  }
  if (n) out[n - 1] = far_plane;
  return out;
}

glsl::ShadowCascadePush shadow_cascade_push(const SunShadowParams& s, float camera_near) {
  glsl::ShadowCascadePush p{};
  const uint32_t n = std::clamp<uint32_t>(s.shadow_cascades, 1, glsl::kShadowMaxCascades);
  const float near_plane = std::max(camera_near, 1e-3f);
  const std::vector<float> splits = cascade_splits(n, near_plane, std::max(s.shadow_distance, 2 * near_plane), s.shadow_split_lambda);
  float sp[4];
  for (uint32_t i = 0; i < 4; ++i) sp[i] = splits[std::min(i, n - 1)];
  p.splits = {sp[0], sp[1], sp[2], sp[3]};
  p.params = {float(n), float(shadow_map_resolution(s)), s.shadow_caster_range, near_plane};
  p.area = {s.shadow_filter_radius, s.shadow_march_distance, s.shadow_bias, s.shadow_normal_offset};
  p.counts = {std::clamp<uint32_t>(s.shadow_taps, 1, glsl::kShadowMaxTaps), std::max<uint32_t>(s.shadow_march_steps, 1), 0,
              s.shadow_minmax_early_out ? 1u : 0u};
  p.blend = {std::max(s.shadow_cascade_blend, 0.0f), 0, 0, 0};
  return p;
}

ShadowBasisCpu shadow_basis(Vec3 sun_dir) {
  ShadowBasisCpu b;
  b.s = normalize(sun_dir);
  const Vec3 ref = std::fabs(b.s.y) < 0.99f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  b.r = normalize(cross(ref, b.s));
  b.u = cross(b.s, b.r);
  return b;
}

Vec2 slice_sphere(float n, float f, float tan_y, float aspect) {
  const float a2 = tan_y * tan_y * (1.0f + aspect * aspect);
  const float c = std::min(0.5f * (f + n) * (1.0f + a2), f);
  const float r = std::max(std::sqrt((c - n) * (c - n) + a2 * n * n), std::sqrt((f - c) * (f - c) + a2 * f * f));
  return {c, r};
}

ShadowCascadeCpu shadow_cascade(uint32_t i, const ShadowCameraCpu& cam, const ShadowBasisCpu& b,
                                const glsl::ShadowCascadePush& p) {
  const float splits[4] = {p.splits.x, p.splits.y, p.splits.z, p.splits.w};
  const float n = i == 0 ? p.params.w : splits[i - 1];
  const float f = splits[i];
  const Vec2 sphere = slice_sphere(n, f, cam.tan_y, cam.aspect);
  const float res = p.params.y;
  const float texel = 2.0f * sphere.y / (res - 2.0f);
  const Vec3 centre = cam.forward * sphere.x;
  const float cam_x = dot(cam.position, b.r), cam_y = dot(cam.position, b.u);
  const float wx = cam_x + dot(centre, b.r), wy = cam_y + dot(centre, b.u);
  ShadowCascadeCpu c;
  c.offset_x = std::floor(wx / texel) * texel - cam_x;
  c.offset_y = std::floor(wy / texel) * texel - cam_y;
  c.half_extent = 0.5f * texel * res;
  c.z_top = dot(centre, b.s) + sphere.y + p.params.z;
  c.z_range = 2.0f * sphere.y + p.params.z;
  return c;
}

Vec3 shadow_project(const ShadowCascadeCpu& c, const ShadowBasisCpu& b, Vec3 x_rel) {
  const float lx = dot(x_rel, b.r) - c.offset_x, ly = dot(x_rel, b.u) - c.offset_y;
  return {lx / (2.0f * c.half_extent) + 0.5f, ly / (2.0f * c.half_extent) + 0.5f, (c.z_top - dot(x_rel, b.s)) / c.z_range};
}

uint32_t select_cascade(const ShadowCameraCpu& cam, const ShadowBasisCpu& b, const glsl::ShadowCascadePush& p,
                        Vec3 x_rel, float margin_m, float margin_texels) {
  for (uint32_t i = 0; i < uint32_t(p.params.x); ++i) {
    const ShadowCascadeCpu c = shadow_cascade(i, cam, b, p);
    const Vec3 q = shadow_project(c, b, x_rel);
    const float m = margin_m / (2.0f * c.half_extent) + margin_texels / p.params.y;
    if (q.x >= m && q.y >= m && q.x <= 1.0f - m && q.y <= 1.0f - m && q.z >= 0.0f && q.z <= 1.0f) return i;
  }
  return glsl::kShadowMaxCascades;
}

float cascade_blend_weight(const ShadowCameraCpu& cam, const ShadowBasisCpu& b, const glsl::ShadowCascadePush& p,
                           uint32_t i, Vec3 x_rel, float margin_m, float margin_texels) {
  const float band = p.blend.x;
  if (!(band > 0.0f) || i + 1 >= uint32_t(p.params.x)) return 0.0f;
  const ShadowCascadeCpu c = shadow_cascade(i, cam, b, p);
  const Vec3 q = shadow_project(c, b, x_rel);
  const float m = margin_m / (2.0f * c.half_extent) + margin_texels / p.params.y;
  const float d = std::min(std::min(q.x - m, q.y - m), std::min(1.0f - m - q.x, 1.0f - m - q.y));
  const float w = std::clamp(1.0f - d / band, 0.0f, 1.0f);
  if (w <= 0.0f) return 0.0f;
  const ShadowCascadeCpu n = shadow_cascade(i + 1, cam, b, p);
  const Vec3 qn = shadow_project(n, b, x_rel);
  const float mn = margin_m / (2.0f * n.half_extent) + margin_texels / p.params.y;
  const bool held = qn.x >= mn && qn.y >= mn && qn.x <= 1.0f - mn && qn.y <= 1.0f - mn && qn.z >= 0.0f && qn.z <= 1.0f;
  return held ? w : 0.0f;
}

Vec2 disk_tap(uint32_t k, uint32_t n, float rotation) {
  const float r = std::sqrt((float(k) + 0.5f) / float(n));
  const float a = float(k) * 2.39996323f + rotation;
  return {r * std::cos(a), r * std::sin(a)};
}

float shadow_tap(const FloatImage& map, uint32_t cascade, float u, float v, float z, uint32_t res) {
  const float tx = u * float(res) - 0.5f, ty = v * float(res) - 0.5f;
  const float ix = std::floor(tx), iy = std::floor(ty);
  const float fx = tx - ix, fy = ty - iy;
  const float top = float(res) - 1.0f;
  const uint32_t ax = uint32_t(std::clamp(ix, 0.0f, top)), ay = uint32_t(std::clamp(iy, 0.0f, top));
  const uint32_t bx = uint32_t(std::clamp(ix + 1.0f, 0.0f, top)), by = uint32_t(std::clamp(iy + 1.0f, 0.0f, top));
  const uint32_t x0 = cascade * res;
  auto lit = [&](uint32_t x, uint32_t y) { return map.at(x0 + x, y, 0) >= z ? 1.0f : 0.0f; };
  const float top_row = lit(ax, ay) + (lit(bx, ay) - lit(ax, ay)) * fx;
  const float bottom_row = lit(ax, by) + (lit(bx, by) - lit(ax, by)) * fx;
  return top_row + (bottom_row - top_row) * fy;
}

}  // namespace gib

namespace gib {

std::vector<Slot> shadow_filter_slots(const char* out) {
  return {{"gbuffer_position", Access::read},
          {"gbuffer_normal", Access::read},
          {"shadow_map", Access::read},
          {"shadow_minmax", Access::read},
          {out, Access::write, ResourceDesc{Format::r32_float, SizeRule::render}.with(unit_values())}};
}

void record_shadow_filter(RecordContext& ctx, const char* shader, const char* out) {
  using namespace glsl;
  ShadowCascadePush push = shadow_cascade_push(ctx.settings.params<SunShadowParams>(), ctx.scene.camera.near_plane);
  record_compute(ctx, {.shader = shader,
                       .images = {{kShadowBindMap, "shadow_map", false, true},  // sampled: gathered
                                  {kShadowBindMinMax, "shadow_minmax"},
                                  {kShadowBindPosition, "gbuffer_position"},
                                  {kShadowBindNormal, "gbuffer_normal"},
                                  {kShadowBindOut, out}},
                       .groups_x = div_up(ctx.width(out), kShadowGroup),
                       .groups_y = div_up(ctx.height(out), kShadowGroup),
                       .push = &push,
                       .push_bytes = sizeof(push)});
}

}  // namespace gib
