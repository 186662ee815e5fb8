#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting_shared.h"

namespace gib {
namespace {

class DeferredLightingPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    PassDecl d;
    d.name = "deferred_lighting";
    const DeferredSettings& ds = s.params<DeferredSettings>();
    d.traces_rays = walks_bvh(scene, ds);  // BVH walk in the shader (PassDecl::traces_rays)
    d.slots = direct_light_slots(ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values()));
    const bool vrcs = ds.vrcs && ds.tile_classification;
    if (ds.tile_classification) d.slots.push_back({"tile_workloads", Access::read});
    if (vrcs) {
      // Next frame's rate reads this frame's tone-mapped luminance (read_prev): one float per
      // pixel kept across frames, not a second copy of the RGBA32F lighting.
      ResourceDesc luma{Format::r32_float, SizeRule::render};
      luma.persistent = true;
      luma.values = unit_values();
      d.slots.push_back({"vrcs_rates", Access::read_write});
      d.slots.push_back({"vrcs_luma", Access::write, luma});
    }
    const std::string_view vis = sun_visibility_slot(ds);
    if (!vis.empty() && scene.features().has(Feature::sun)) d.slots.push_back({std::string(vis), Access::read});
    d.work = {{"sky_rays", sky_unoccluded(ds) ? 0.0 : double(s.width) * s.height * ds.sky_rays}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeferredSettings& ds = ctx.settings.params<DeferredSettings>();
    const SceneFeatures f = ctx.scene.features();
    const uint32_t w = ctx.width("direct_light"), h = ctx.height("direct_light");
    const uint32_t tiles_x = div_up(w, kDeferredTile);
    LightPush push{ds.sky_rays, ctx.settings.nan_guards ? 1u : 0u, tiles_x, tiles_x * div_up(h, kDeferredTile),
                   div_up(w, kVrcsTile), ds.sheen_lobe ? 1u : 0u, 0, 0};
    static_assert(sizeof(push) == 32, "LightPush must match deferred_lighting.glsl's push block");
    std::vector<ImageBinding> images = {{kLightBindVbuffer, "vbuffer"},        {kLightBindAlbedo, "gbuffer_albedo"},
                                              {kLightBindNormal, "gbuffer_normal"},    {kLightBindPosition, "gbuffer_position"},
                                              {kLightBindEmissive, "gbuffer_emissive"}, {kLightBindOut, "direct_light"}};
    std::vector<SpecConstant> spec = {{kLightSpecSun, f.has(Feature::sun)},
                                      {kLightSpecSky, f.has(Feature::sky)},
                                      {kLightSpecLocal, f.has(Feature::local_lights)},
                                      {kLightSpecAlpha, f.has(Feature::alpha_tested)},
                                      {kLightSpecEmissive, f.has(Feature::emissive)},
                                      {kLightSpecSkyUnoccluded, sky_unoccluded(ds)}};
    // The shadow_mapped mode (or a technique's own sun visibility) in a scene with a sun: the
    // sun's visibility from its slot, by the kernels compiled with it (*_sun_visibility.comp).
    const std::string vis(sun_visibility_slot(ds));
    const bool by_slot = !vis.empty() && f.has(Feature::sun);
    if (by_slot) images.push_back({kLightBindSunVisibility, vis.c_str()});
    auto kernel = [by_slot](std::string stem) { return (by_slot ? stem + "_sun_visibility" : stem) + ".comp"; };
    if (!ds.tile_classification) {
      const std::string uber = kernel("deferred_lighting_uber");
      record_compute(ctx, {.shader = uber.c_str(),
                           .images = images,
                           .groups_x = div_up(w, kLightingGroup),
                           .groups_y = div_up(h, kLightingGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = spec});
      return;
    }
    spec.push_back({kLightSpecWorkload, 0});
    std::vector<BufferBinding> buffers = {{kLightBindWorkloads, "tile_workloads"}};
    if (ds.vrcs) {
      buffers.push_back({kLightBindRates, "vrcs_rates"});
      images.push_back({kLightBindLuma, "vrcs_luma"});
    }
    const std::string shader = kernel(!ds.vrcs                               ? "deferred_lighting"
                                      : ctx.gpu.info().subgroup_arithmetic ? "deferred_lighting_vrcs"
                                                                           : "deferred_lighting_vrcs_plain");
    for (uint32_t workload = 0; workload < kWorkloadCount; ++workload) {
      spec.back().value = workload;
      record_compute(ctx, {.shader = shader.c_str(),
                           .images = images,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = spec,
                           .buffers = buffers,
                           .indirect = "tile_workloads",
                           .indirect_offset = 16ull * workload});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_deferred_lighting_pass() { return std::make_unique<DeferredLightingPass>(); }

}  // namespace gib
