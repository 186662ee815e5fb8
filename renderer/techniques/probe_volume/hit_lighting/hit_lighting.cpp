#include "renderer/techniques/probe_volume/hit_lighting/hit_lighting.h"

#include "renderer/techniques/probe_volume/hit_lighting/hit_lighting_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class HitLightingPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    PassDecl d;
    d.name = "hit_lighting";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    const SizeRule size = pv_pixel_size(p);
    d.slots = {{"pixel_hits", Access::read},        {"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},    {"gbuffer_emissive", Access::read},
               {"probe_state", Access::read},       {"probe_irradiance", Access::read},
               {"probe_radiance", Access::read},    {"probe_visibility", Access::read},
               {"pixel_sh", Access::write, ResourceDesc{Format::rg32_uint, size}}};
    d.work = {{"rays", pv_ray_pixels(s)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    PvHitLightingPush push{make_pv_params(ctx.settings, ctx.frame)};
    const Image& sh = ctx.image("pixel_sh");
    const SceneFeatures f = ctx.scene.features();
    record_compute(ctx, {.shader = "hit_lighting.comp",
                         .images = {{kPvHitLightingBindPosition, "gbuffer_position"},
                                    {kPvHitLightingBindNormal, "gbuffer_normal"},
                                    {kPvHitLightingBindEmissive, "gbuffer_emissive"},
                                    {kPvHitLightingBindHits, "pixel_hits"},
                                    {kPvHitLightingBindSh, "pixel_sh"}},
                         .groups_x = div_up(sh.width(), kPvHitLightingGroup),
                         .groups_y = div_up(sh.height(), kPvHitLightingGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kPvHitLightingSpecAlpha, f.has(Feature::alpha_tested)},
                                            {kPvHitLightingSpecSun, f.has(Feature::sun)},
                                            {kPvHitLightingSpecLocal, f.has(Feature::local_lights)}},
                         .buffers = {{kPvHitLightingBindState, "probe_state"},
                                     {kPvHitLightingBindIrradiance, "probe_irradiance"},
                                     {kPvHitLightingBindRadiance, "probe_radiance"},
                                     {kPvHitLightingBindVisibility, "probe_visibility"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_hit_lighting_pass() { return std::make_unique<HitLightingPass>(); }

}  // namespace gib
