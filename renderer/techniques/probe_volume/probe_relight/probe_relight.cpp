#include "renderer/techniques/probe_volume/probe_relight/probe_relight.h"

#include "renderer/techniques/probe_volume/probe_relight/probe_relight_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeRelightPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    const uint64_t texels = uint64_t(p.probe_budget) * glsl::kPvGbufferTexels;
    PassDecl d;
    d.name = "probe_relight";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    auto buffer = [](uint64_t bytes) { return pv_buffer(bytes, false); };
    ResourceDesc radiance = buffer(texels * 16);
    radiance.values = non_negative_values().layout(4, 0, 4);
    ResourceDesc local = buffer(texels * 4);
    local.values = non_negative_values().layout(1, 0, 1);
    d.slots = {{"probe_gb_material", Access::read},
               {"probe_gb_normal", Access::read},
               {"probe_gb_depth", Access::read},
               {"probe_selection", Access::read},
               {"probe_state", Access::read_write},
               {"probe_irradiance", Access::read_write},
               {"probe_radiance", Access::read_write},
               {"probe_visibility", Access::read_write},
               {"probe_texel_lists", Access::write, buffer(sizeof(glsl::PvTexelLists) + texels * 8)},
               {"probe_texel_radiance", Access::write, radiance},
               {"probe_texel_local", Access::write, local}};
    d.work = {{"texels", double(texels)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const ProbeVolumeSettings& p = ctx.settings.params<ProbeVolumeSettings>();
    PvRelightPush push{make_pv_params(ctx.settings, ctx.frame)};
    // Texels no kernel writes this frame (a quarter probe's repeated texels, entries past the
    // selection) hold zeros, not last frame's or uninitialised values.
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("probe_texel_radiance"), 0);
    ctx.cmd.fill(ctx.buffer("probe_texel_local"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const SceneFeatures f = ctx.scene.features();
    const std::vector<BufferBinding> buffers{
        {kPvRelightBindState, "probe_state"},          {kPvRelightBindSelection, "probe_selection"},
        {kPvRelightBindMaterial, "probe_gb_material"}, {kPvRelightBindNormal, "probe_gb_normal"},
        {kPvRelightBindDepth, "probe_gb_depth"},       {kPvRelightBindTexels, "probe_texel_lists"},
        {kPvRelightBindRadiance, "probe_texel_radiance"}, {kPvRelightBindLocal, "probe_texel_local"},
        {kPvRelightBindIrradiance, "probe_irradiance"}, {kPvRelightBindProbeRadiance, "probe_radiance"},
        {kPvRelightBindVisibility, "probe_visibility"}};
    auto dispatch = [&](uint32_t kernel, const char* label, uint32_t groups, const char* indirect, uint64_t offset) {
      ctx.cmd.begin_label(label);
      record_compute(ctx, {.shader = "probe_relight.comp",
                           .groups_x = groups,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kPvRelightSpecAlpha, f.has(Feature::alpha_tested)},
                                              {kPvRelightSpecLocal, f.has(Feature::local_lights)},
                                              {kPvRelightSpecSky, f.has(Feature::sky)},
                                              {kPvRelightSpecKernel, kernel}},
                           .buffers = buffers,
                           .indirect = indirect,
                           .indirect_offset = offset});
      ctx.cmd.end_label();
      ctx.cmd.barrier(kStageCompute, kStageCompute);
    };
    dispatch(kPvRelightRescale, "probe_relight/rescale", div_up(pv_probe_count(p), kPvRelightGroup), nullptr, 0);
    dispatch(kPvRelightClassify, "probe_relight/classify", 1, "probe_selection", offsetof(PvSelection, all_args));
    dispatch(kPvRelightArgs, "probe_relight/args", 1, nullptr, 0);
    dispatch(kPvRelightHit, "probe_relight/hit", 1, "probe_texel_lists", offsetof(PvTexelLists, hit_args));
    dispatch(kPvRelightMiss, "probe_relight/miss", 1, "probe_texel_lists", offsetof(PvTexelLists, miss_args));
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_relight_pass() { return std::make_unique<ProbeRelightPass>(); }

}  // namespace gib
