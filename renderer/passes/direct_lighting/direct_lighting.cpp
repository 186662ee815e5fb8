#include "renderer/passes/direct_lighting/direct_lighting.h"

#include "renderer/passes/direct_lighting/direct_lighting_shared.h"

namespace gib {
namespace {

class DirectLightingPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "direct_lighting";
    d.slots = direct_light_slots(ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values()));
    d.work = {{"sky_rays", double(s.width) * s.height * s.params<DirectLightingParams>().sky_rays}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    SceneFeatures f = ctx.scene.features();
    DirectPush push{ctx.settings.params<DirectLightingParams>().sky_rays, ctx.settings.nan_guards ? 1u : 0u, 0, 0};
    static_assert(sizeof(push) == 16, "DirectPush must match direct_lighting.comp's push block");
    record_compute(ctx, {.shader = "direct_lighting.comp",
                         .images = {{kDirectBindVbuffer, "vbuffer"},
                                    {kDirectBindAlbedo, "gbuffer_albedo"},
                                    {kDirectBindNormal, "gbuffer_normal"},
                                    {kDirectBindPosition, "gbuffer_position"},
                                    {kDirectBindEmissive, "gbuffer_emissive"},
                                    {kDirectBindOut, "direct_light"}},
                         .groups_x = div_up(ctx.width("direct_light"), kDirectGroup),
                         .groups_y = div_up(ctx.height("direct_light"), kDirectGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kDirectSpecSun, f.has(Feature::sun)},
                                            {kDirectSpecSky, f.has(Feature::sky)},
                                            {kDirectSpecLocal, f.has(Feature::local_lights)},
                                            {kDirectSpecAlpha, f.has(Feature::alpha_tested)},
                                            {kDirectSpecEmissive, f.has(Feature::emissive)}}});
  }
};

}  // namespace

std::vector<Slot> direct_light_slots(const ResourceDesc& out) {
  return {{"vbuffer", Access::read},          {"gbuffer_albedo", Access::read},   {"gbuffer_normal", Access::read},
          {"gbuffer_position", Access::read}, {"gbuffer_emissive", Access::read}, {"direct_light", Access::write, out}};
}

std::unique_ptr<Pass> make_direct_lighting_pass() { return std::make_unique<DirectLightingPass>(); }

}  // namespace gib
