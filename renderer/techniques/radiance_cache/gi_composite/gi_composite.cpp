#include "renderer/techniques/radiance_cache/gi_composite/gi_composite.h"

#include "renderer/passes/composite/composite.h"
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite_shared.h"
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {
namespace {

class GiCompositePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "gi_composite";
    d.slots = {{"direct_light", Access::read},
               {"gbuffer_albedo", Access::read},
               {"gi_history", Access::read},
               {"gi_history_direct", Access::read},
               {"exposure", Access::read}};
    for (Slot& s : composite_output_slots()) d.slots.push_back(std::move(s));
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    record_compute(ctx, {.shader = gi_history_shader("gi_composite", r.history_format),
                         .images = {{kGiCompositeBindDirect, "direct_light"},
                                    {kGiCompositeBindAlbedo, "gbuffer_albedo"},
                                    {kGiCompositeBindHistory, "gi_history"},
                                    {kGiCompositeBindHistoryDirect, "gi_history_direct"},
                                    {kGiCompositeBindColor, "final_color"},
                                    {kGiCompositeBindIndirect, "indirect_diffuse"},
                                    {kGiCompositeBindDirectOut, "direct_radiance"}},
                         .groups_x = div_up(ctx.width("final_color"), kGiCompositeGroup),
                         .groups_y = div_up(ctx.height("final_color"), kGiCompositeGroup),
                         .scene = false,
                         .buffers = {{kGiCompositeBindExposure, "exposure"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_gi_composite_pass() { return std::make_unique<GiCompositePass>(); }

}  // namespace gib
