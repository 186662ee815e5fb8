#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting_shared.h"

namespace gib {
namespace {

class DeferredLightingPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "deferred_lighting";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    const DeferredSettings& ds = s.params<DeferredSettings>();
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
    d.work = {{"sky_rays", double(s.width) * s.height * s.params<DeferredSettings>().sky_rays}};
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
                                      {kLightSpecEmissive, f.has(Feature::emissive)}};
    if (!ds.tile_classification) {
      record_compute(ctx, {.shader = "deferred_lighting_uber.comp",
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
    for (uint32_t workload = 0; workload < kWorkloadCount; ++workload) {
      spec.back().value = workload;
      record_compute(ctx, {.shader = !ds.vrcs ? "deferred_lighting.comp"
                                    : ctx.gpu.info().subgroup_arithmetic ? "deferred_lighting_vrcs.comp"
                                                                         : "deferred_lighting_vrcs_plain.comp",
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
