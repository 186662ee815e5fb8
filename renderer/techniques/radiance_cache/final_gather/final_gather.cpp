#include "renderer/techniques/radiance_cache/final_gather/final_gather.h"

#include <algorithm>
#include <cmath>

#include "renderer/techniques/radiance_cache/final_gather/final_gather_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

class FinalGatherPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const SizeRule size = gather_size_rule(s.params<RadianceCacheSettings>());
    const ResourceDesc sh = ResourceDesc{Format::rgba16_float, size}.with(  // x L0, yzw L1
        non_negative_values().allow_negative(kChannelG | kChannelB | kChannelA));
    ResourceDesc stats{Format::buffer, SizeRule::buffer};
    stats.bytes = glsl::kGatherStatCount * sizeof(uint32_t);
    PassDecl d;
    d.name = "final_gather";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    d.slots = {{"vbuffer", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_position", Access::read},
               {"gbuffer_position", Access::read_prev},
               {"final_color", Access::read_prev},
               {"rc_cells", Access::read},
               {"probe_irradiance", Access::read},
               {"probe_visibility", Access::read},
               {"exposure", Access::read},
               {"gather_sh_r", Access::write, sh},
               {"gather_sh_g", Access::write, sh},
               {"gather_sh_b", Access::write, sh},
               {"gather_direct", Access::write, ResourceDesc{Format::rgba16_float, size}.with(non_negative_values())},
               {"gather_hit_distance", Access::write, ResourceDesc{Format::r32_float, size}.with(non_negative_values())},
               {"gather_stats", Access::write, stats}};
    // Which source answered the gather rays (bench prints them): a ray answered by the volumes
    // misses the direct light at its hit, so that count bounds the fallback's bias.
    d.measured = {{"rays_screen_cache", "gather_stats", glsl::kGatherStatScreen * sizeof(uint32_t)},
                  {"rays_world_cache", "gather_stats", glsl::kGatherStatWorld * sizeof(uint32_t)},
                  {"rays_volume", "gather_stats", glsl::kGatherStatVolume * sizeof(uint32_t)},
                  {"rays_sky", "gather_stats", glsl::kGatherStatSky * sizeof(uint32_t)}};
    const double g = gather_divisor(s.params<RadianceCacheSettings>());
    d.work = {{"rays", std::ceil(s.width / g) * std::ceil(s.height / g)}};  // one per gather pixel
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    struct {
      RcParams rc;
      GatherPush gather;
    } push{make_rc_params(ctx.settings, ctx.frame),
           {gather_divisor(r), ctx.frame > 0 ? 1u : 0u, r.sky_rays == 0 ? 1u : 0u, 0}};

    ComputePipelineDesc desc;
    desc.shader = "final_gather.comp";
    desc.bindings = scene_bindings();
    desc.push_constant_bytes = sizeof(push);
    desc.spec_constants = {{kGatherSpecAlpha, ctx.scene.features().has(Feature::alpha_tested)}};
    std::vector<Bind> binds = ctx.scene_gpu.binds();
    auto image = [&](uint32_t binding, const Image& img) {
      desc.bindings.push_back({binding, DescriptorKind::storage_image});
      binds.push_back({binding, nullptr, &img});
    };
    auto buffer = [&](uint32_t binding, const Buffer& buf) {
      desc.bindings.push_back({binding, DescriptorKind::storage_buffer});
      binds.push_back({binding, &buf, nullptr});
    };
    image(kGatherBindNormal, ctx.image("gbuffer_normal"));
    image(kGatherBindPosition, ctx.image("gbuffer_position"));
    image(kGatherBindPrevPosition, ctx.prev_image("gbuffer_position"));
    image(kGatherBindPrevColor, ctx.image("final_color"));  // only read_prev: last frame's copy
    image(kGatherBindProbeIrradiance, ctx.image("probe_irradiance"));
    image(kGatherBindProbeVisibility, ctx.image("probe_visibility"));
    buffer(kGatherBindCells, ctx.buffer("rc_cells"));
    buffer(kGatherBindStats, ctx.buffer("gather_stats"));
    buffer(kGatherBindExposure, ctx.buffer("exposure"));
    image(kGatherBindShR, ctx.image("gather_sh_r"));
    image(kGatherBindShG, ctx.image("gather_sh_g"));
    image(kGatherBindShB, ctx.image("gather_sh_b"));
    image(kGatherBindHitDistance, ctx.image("gather_hit_distance"));
    image(kGatherBindDirect, ctx.image("gather_direct"));
    image(kGatherBindVbuffer, ctx.image("vbuffer"));

    ctx.cmd.fill(ctx.buffer("gather_stats"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    auto pipeline = ctx.gpu.compute_pipeline(desc);
    ctx.cmd.bind(*pipeline, binds, &push, sizeof(push));
    ctx.cmd.dispatch(div_up(ctx.width("gather_hit_distance"), kGatherGroup),
                     div_up(ctx.height("gather_hit_distance"), kGatherGroup));
  }
};

}  // namespace

std::unique_ptr<Pass> make_final_gather_pass() { return std::make_unique<FinalGatherPass>(); }

}  // namespace gib
