#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise.h"

#include <algorithm>

#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class PixelDenoisePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    PassDecl d;
    d.name = "pixel_denoise";
    const SizeRule size = pv_pixel_size(p);
    ResourceDesc history{Format::rgba32_float, size};
    history.persistent = true;
    // Y0 >= 0 and the signed band-1 vector; Co, Cg (signed), frames, view depth.
    const ResourceDesc y = ResourceDesc{Format::rgba32_float, size}.with(
        non_negative_values().allow_negative(kChannelG | kChannelB | kChannelA));
    const ResourceDesc c = ResourceDesc{Format::rgba32_float, size}.with(
        non_negative_values().allow_negative(kChannelR | kChannelG));
    ResourceDesc history_y = history, history_c = history;
    history_y.values = y.values;
    history_c.values = c.values;
    // The anti-lag's fast history of Y0, the spatial noise estimate's mean over frames, its frames.
    ResourceDesc history_fast{Format::rgba32_float, size};
    history_fast.persistent = true;
    history_fast.values = non_negative_values();
    d.slots = {{"pixel_sh", Access::read},
               {"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_emissive", Access::read},
               {"pixel_history_y", Access::write, history_y},
               {"pixel_history_c", Access::write, history_c},
               {"pixel_history_y", Access::read_prev},
               {"pixel_history_c", Access::read_prev},
               {"pixel_history_fast", Access::write, history_fast},
               {"pixel_history_fast", Access::read_prev},
               {"pixel_gi_y", Access::write, y},
               {"pixel_gi_c", Access::write, c}};
    d.work = {{"pixels", pv_ray_pixels(s)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const ProbeVolumeSettings& p = ctx.settings.params<ProbeVolumeSettings>();
    PvDenoisePush push{make_pv_params(ctx.settings, ctx.frame),
                       {p.anti_lag_sigma, float(std::max(p.fast_history_frames, 1u)), 0.0f, 0.0f}};
    const Image& out = ctx.image("pixel_gi_y");
    for (uint32_t kernel : {kPvDenoiseFilter, kPvDenoisePoisson}) {
      ctx.cmd.begin_label(kernel == kPvDenoiseFilter ? "pixel_denoise/filter" : "pixel_denoise/poisson");
      record_compute(ctx, {.shader = "pixel_denoise.comp",
                           .images = {{kPvDenoiseBindPosition, "gbuffer_position"},
                                      {kPvDenoiseBindNormal, "gbuffer_normal"},
                                      {kPvDenoiseBindEmissive, "gbuffer_emissive"},
                                      {kPvDenoiseBindSh, "pixel_sh"},
                                      {kPvDenoiseBindPrevY, "pixel_history_y", true},
                                      {kPvDenoiseBindPrevC, "pixel_history_c", true},
                                      {kPvDenoiseBindHistoryY, "pixel_history_y"},
                                      {kPvDenoiseBindHistoryC, "pixel_history_c"},
                                      {kPvDenoiseBindGiY, "pixel_gi_y"},
                                      {kPvDenoiseBindGiC, "pixel_gi_c"},
                                      {kPvDenoiseBindPrevFast, "pixel_history_fast", true},
                                      {kPvDenoiseBindFast, "pixel_history_fast"}},
                           .groups_x = div_up(out.width(), kPvDenoiseGroup),
                           .groups_y = div_up(out.height(), kPvDenoiseGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kPvDenoiseSpecKernel, kernel}},
                           .scene = true});
      ctx.cmd.end_label();
      ctx.cmd.barrier(kStageCompute, kStageCompute);
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_pixel_denoise_pass() { return std::make_unique<PixelDenoisePass>(); }

}  // namespace gib
