#include "renderer/techniques/probe_volume/screen_trace/screen_trace.h"

#include "renderer/techniques/probe_volume/probe_volume_params.h"
#include "renderer/techniques/probe_volume/screen_trace/screen_trace_shared.h"

namespace gib {
namespace {

class ScreenTracePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    PassDecl d;
    d.name = "screen_trace";
    const SizeRule size = pv_pixel_size(p);
    ResourceDesc stats{Format::buffer, SizeRule::buffer};
    stats.bytes = 16;
    d.slots = {{"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_emissive", Access::read},
               {"gbuffer_albedo", Access::read},
               {"probe_state", Access::read},
               {"pixel_hits", Access::write, ResourceDesc{Format::rgba32_uint, size}},
               {"pixel_trace_stats", Access::write, stats}};
    d.work = {{"rays", pv_ray_pixels(s)},
              {"steps", pv_ray_pixels(s) * p.screen_steps}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const ProbeVolumeSettings& p = ctx.settings.params<ProbeVolumeSettings>();
    PvScreenTracePush push{make_pv_params(ctx.settings, ctx.frame), {float(p.screen_steps), p.screen_thickness, p.screen_resume ? 1.0f : 0.0f, 0}};
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("pixel_trace_stats"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const Image& hits = ctx.image("pixel_hits");
    record_compute(ctx, {.shader = "screen_trace.comp",
                         .images = {{kPvScreenTraceBindPosition, "gbuffer_position"},
                                    {kPvScreenTraceBindNormal, "gbuffer_normal"},
                                    {kPvScreenTraceBindEmissive, "gbuffer_emissive"},
                                    {kPvScreenTraceBindAlbedo, "gbuffer_albedo"},
                                    {kPvScreenTraceBindHits, "pixel_hits"}},
                         .groups_x = div_up(hits.width(), kPvScreenTraceGroup),
                         .groups_y = div_up(hits.height(), kPvScreenTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kPvScreenTraceBindState, "probe_state"}, {kPvScreenTraceBindStats, "pixel_trace_stats"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_screen_trace_pass() { return std::make_unique<ScreenTracePass>(); }

}  // namespace gib
