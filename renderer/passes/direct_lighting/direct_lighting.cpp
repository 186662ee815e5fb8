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
    d.slots = direct_light_slots(ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values()));
    const DirectLightingParams& params = s.params<DirectLightingParams>();
    d.traces_rays = walks_bvh(scene, params);  // BVH walk in the shader (PassDecl::traces_rays)
    const std::string_view vis = sun_visibility_slot(params);
    if (!vis.empty() && scene.features().has(Feature::sun)) d.slots.push_back({std::string(vis), Access::read});
    d.work = {{"sky_rays", sky_unoccluded(params) ? 0.0 : double(s.width) * s.height * params.sky_rays}};
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
    const std::string vis(sun_visibility_slot(params));
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
                                            {kDirectSpecEmissive, f.has(Feature::emissive)},
                                            {kDirectSpecSkyUnoccluded, sky_unoccluded(params)}}});
  }
};

}  // namespace

std::string_view sun_visibility_slot(const DirectLightingParams& p) {
  if (!p.sun_visibility.empty()) return p.sun_visibility;
  return p.direct_light == uint32_t(DirectLightMode::shadow_mapped) ? "shadow_pcf" : "";
}

bool walks_bvh(const Scene& scene, const DirectLightingParams& p) {
  const SceneFeatures f = scene.features();
  return !sky_unoccluded(p) || (f.has(Feature::local_lights) && p.local_lights) ||
         (f.has(Feature::sun) && sun_visibility_slot(p).empty());
}

std::vector<Slot> direct_light_slots(const ResourceDesc& out) {
  return {{"vbuffer", Access::read},          {"gbuffer_albedo", Access::read},   {"gbuffer_normal", Access::read},
          {"gbuffer_position", Access::read}, {"gbuffer_emissive", Access::read}, {"direct_light", Access::write, out}};
}

std::unique_ptr<Pass> make_direct_lighting_pass() { return std::make_unique<DirectLightingPass>(); }

}  // namespace gib
