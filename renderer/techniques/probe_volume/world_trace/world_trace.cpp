#include "renderer/techniques/probe_volume/world_trace/world_trace.h"

#include "renderer/techniques/probe_volume/probe_volume_params.h"
#include "renderer/techniques/probe_volume/world_trace/world_trace_shared.h"

namespace gib {
namespace {

class WorldTracePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "world_trace";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    d.slots = {{"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_emissive", Access::read},
               {"probe_state", Access::read},
               {"pixel_hits", Access::read_write}};
    d.work = {{"rays", pv_ray_pixels(s)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    PvWorldTracePush push{make_pv_params(ctx.settings, ctx.frame)};
    const Image& hits = ctx.image("pixel_hits");
    record_compute(ctx, {.shader = "world_trace.comp",
                         .images = {{kPvWorldTraceBindPosition, "gbuffer_position"},
                                    {kPvWorldTraceBindNormal, "gbuffer_normal"},
                                    {kPvWorldTraceBindEmissive, "gbuffer_emissive"},
                                    {kPvWorldTraceBindHits, "pixel_hits"}},
                         .groups_x = div_up(hits.width(), kPvWorldTraceGroup),
                         .groups_y = div_up(hits.height(), kPvWorldTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kPvWorldTraceSpecAlpha, ctx.scene.features().has(Feature::alpha_tested)}},
                         .buffers = {{kPvWorldTraceBindState, "probe_state"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_world_trace_pass() { return std::make_unique<WorldTracePass>(); }

}  // namespace gib
