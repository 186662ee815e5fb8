#include "renderer/passes/shadow_maps/shadow_maps.h"

#include <algorithm>

#include "renderer/passes/shadow_cascades.h"
#include "renderer/passes/shadow_maps/shadow_maps_shared.h"

namespace gib {
namespace {

class ShadowMapsPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<SunShadowParams>();
    const uint32_t res = shadow_map_resolution(g), n = std::clamp<uint32_t>(g.shadow_cascades, 1, glsl::kShadowMaxCascades);
    PassDecl d;
    d.name = "shadow_maps";
    d.kind = PassKind::graphics;
    d.needs = Feature::sun;
    ResourceDesc map{Format::r32_float, SizeRule::fixed, res * n, res};
    ResourceDesc depth{Format::d32_float, SizeRule::fixed, res * n, res};
    d.slots = {{"shadow_map", Access::write, map.with(unit_values())}, {"shadow_depth", Access::write, depth}};
    d.work = {{"shadow_texels", double(res) * res * n}};
    return d;
  }

  void record(RecordContext& ctx) override {
    const auto& g = ctx.settings.params<SunShadowParams>();
    glsl::ShadowCascadePush push = shadow_cascade_push(g, ctx.scene.camera.near_plane);
    static_assert(sizeof(push) == 80, "ShadowCascadePush must match shadow_cascades_shared.h");
    GraphicsPipelineDesc desc;
    desc.vertex_shader = "shadow_maps.vert";
    desc.fragment_shader = "shadow_maps.frag";
    desc.bindings = scene_bindings();
    desc.push_constant_bytes = sizeof(push);
    desc.color_formats = {Format::r32_float};
    desc.depth = true;
    auto pipeline = ctx.gpu.graphics_pipeline(desc);
    const Image* colors[] = {&ctx.image("shadow_map")};
    const float clear[4] = {1, 1, 1, 1};  // nothing between the sun and the far end: lit
    ctx.cmd.begin_rendering(colors, &ctx.image("shadow_depth"), clear);
    const uint32_t res = uint32_t(push.params.y);
    auto binds = ctx.scene_gpu.binds();
    for (uint32_t i = 0; i < uint32_t(push.params.x); ++i) {
      push.counts.z = i;
      ctx.cmd.set_viewport(i * res, 0, res, res);
      ctx.cmd.bind(*pipeline, binds, &push, sizeof(push));
      ctx.cmd.draw(ctx.scene_gpu.triangle_count * 3);
    }
    ctx.cmd.end_rendering();
  }
};

}  // namespace

std::unique_ptr<Pass> make_shadow_maps_pass() { return std::make_unique<ShadowMapsPass>(); }

}  // namespace gib
