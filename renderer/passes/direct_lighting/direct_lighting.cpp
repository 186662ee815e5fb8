#include "renderer/passes/direct_lighting/direct_lighting.h"

#include "renderer/passes/direct_lighting/direct_lighting_shared.h"

#include <string>

namespace gib {
namespace {

class DirectLightingPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    PassDecl d;
    d.name = "direct_lighting";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    d.slots = direct_light_slots(ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values()));
    const std::string_view vis = s.params<DirectLightingParams>().sun_visibility;
    if (!vis.empty() && scene.features().has(Feature::sun)) d.slots.push_back({std::string(vis), Access::read});
    d.work = {{"sky_rays", double(s.width) * s.height * s.params<DirectLightingParams>().sky_rays}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    SceneFeatures f = ctx.scene.features();
    const DirectLightingParams& params = ctx.settings.params<DirectLightingParams>();
    DirectPush push{params.sky_rays, ctx.settings.nan_guards ? 1u : 0u, 0, 0};
    static_assert(sizeof(push) == 16, "DirectPush must match direct_lighting.comp's push block");
    std::vector<ImageBinding> images = {{kDirectBindVbuffer, "vbuffer"},
                                        {kDirectBindAlbedo, "gbuffer_albedo"},
                                        {kDirectBindNormal, "gbuffer_normal"},
                                        {kDirectBindPosition, "gbuffer_position"},
                                        {kDirectBindEmissive, "gbuffer_emissive"},
                                        {kDirectBindOut, "direct_light"}};
    const std::string vis(params.sun_visibility);
    const bool shadowed_by_slot = !vis.empty() && f.has(Feature::sun);
    if (shadowed_by_slot) images.push_back({kDirectBindSunVisibility, vis.c_str()});
    record_compute(ctx, {.shader = shadowed_by_slot ? "direct_lighting_sun_visibility.comp" : "direct_lighting.comp",
                         .images = images,
                         .groups_x = div_up(ctx.width("direct_light"), kDirectGroup),
                         .groups_y = div_up(ctx.height("direct_light"), kDirectGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kDirectSpecSun, f.has(Feature::sun)},
                                            {kDirectSpecSky, f.has(Feature::sky)},
                                            {kDirectSpecLocal, f.has(Feature::local_lights) && params.local_lights},
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
