#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve.h"

#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve_shared.h"
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {
namespace {

class GiResolvePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "gi_resolve";
    d.slots = {{"gi_history", Access::read},
               {"gi_history_direct", Access::read},
               {"exposure", Access::read},
               {"gi_irradiance", Access::write, ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())},
               {"gi_direct_irradiance", Access::write,
                ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    record_compute(ctx, {.shader = gi_history_shader("gi_resolve", r.history_format),
                         .images = {{kGiResolveBindHistory, "gi_history"},
                                    {kGiResolveBindHistoryDirect, "gi_history_direct"},
                                    {kGiResolveBindIrradiance, "gi_irradiance"},
                                    {kGiResolveBindDirectIrradiance, "gi_direct_irradiance"}},
                         .groups_x = div_up(ctx.width("gi_irradiance"), kGiResolveGroup),
                         .groups_y = div_up(ctx.height("gi_irradiance"), kGiResolveGroup),
                         .scene = false,
                         .buffers = {{kGiResolveBindExposure, "exposure"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_gi_resolve_pass() { return std::make_unique<GiResolvePass>(); }

}  // namespace gib
