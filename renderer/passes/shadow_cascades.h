// CPU side of the cascaded sun shadow map (shadow_maps, shadow_minmax, shadows_pcf, gow-ragnarok's
// shadows_contact_hardening): the push constants every shadow pass gets
// (cascade splits from the settings), and mirrors of shadow_cascades.glsl's closed forms (basis,
// slice sphere, cascade, projection, selection, filter disk, filtered tap) that
// tests/test_gow_shadows.cpp checks against the GPU and against known answers.
#pragma once
#include <cstdint>
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/image/float_image.h"
#include "renderer/scene/math.h"
#include "renderer/passes/sun_shadow_params.h"
#include "shadow_cascades_shared.h"

namespace gib {

// Texels per side of one cascade (the setting rounded up to whole min/max tiles).
uint32_t shadow_map_resolution(const SunShadowParams& s);
// Far view distances of cascades 0..n-1 between near and far: lambda * logarithmic + (1 -
// lambda) * uniform (the practical split scheme); the last is `far`.
std::vector<float> cascade_splits(uint32_t n, float near_plane, float far_plane, float lambda);
// The push constants of every shadow pass (counts.z, the cascade to rasterise, left 0).
glsl::ShadowCascadePush shadow_cascade_push(const SunShadowParams& s, float camera_near);

struct ShadowBasisCpu {
  Vec3 r, u, s;
};
struct ShadowCascadeCpu {
  float offset_x = 0, offset_y = 0, half_extent = 0, z_top = 0, z_range = 0;
};
struct ShadowCameraCpu {
  Vec3 position, forward;
  float tan_y = 0, aspect = 1;
};

ShadowBasisCpu shadow_basis(Vec3 sun_dir);
// (centre distance along the view axis, radius) of the slice's bounding sphere.
Vec2 slice_sphere(float n, float f, float tan_y, float aspect);
ShadowCascadeCpu shadow_cascade(uint32_t i, const ShadowCameraCpu& cam, const ShadowBasisCpu& b,
                                const glsl::ShadowCascadePush& p);
Vec3 shadow_project(const ShadowCascadeCpu& c, const ShadowBasisCpu& b, Vec3 x_rel);  // (u, v, depth)
uint32_t select_cascade(const ShadowCameraCpu& cam, const ShadowBasisCpu& b, const glsl::ShadowCascadePush& p,
                        Vec3 x_rel, float margin_m, float margin_texels);  // kShadowMaxCascades: none
// The seam blend: weight of cascade i + 1 at x_rel, whose selected cascade is i (0 at `band` =
// p.blend.x of cascade i's width from the edge of the square select_cascade accepts, 1 at that
// edge; 0 when blending is off, i is the last cascade, or i + 1 does not hold the point).
float cascade_blend_weight(const ShadowCameraCpu& cam, const ShadowBasisCpu& b, const glsl::ShadowCascadePush& p,
                           uint32_t i, Vec3 x_rel, float margin_m, float margin_texels);
Vec2 disk_tap(uint32_t k, uint32_t n, float rotation);
// Filtered comparison against a one-channel shadow-map atlas (cascades side by side, res each).
float shadow_tap(const FloatImage& map, uint32_t cascade, float u, float v, float z, uint32_t res);

}  // namespace gib

namespace gib {
// The slots and the dispatch of a shadow filter pass (shadows_pcf, shadows_contact_hardening):
// reads gbuffer_position, gbuffer_normal, shadow_map, shadow_minmax; writes `out` (r32_float,
// render size, sun visibility in [0, 1]).
std::vector<Slot> shadow_filter_slots(const char* out);
void record_shadow_filter(RecordContext& ctx, const char* shader, const char* out);
}  // namespace gib
