#include "renderer/techniques/gow_ragnarok/ssdo/ssdo.h"

#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/techniques/gow_ragnarok/ssdo/ssdo_shared.h"

namespace gib {
namespace {

class SsdoPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    PassDecl d;
    d.name = "ssdo";
    if (g.ss_combined) return d;  // ssdo_ssgi runs: nothing to write, culled
    d.needs = Feature::local_lights;
    d.slots = {{"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_albedo", Access::read},
               {"ssdo_local_light", Access::write,
                ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())},
               {"ssdo_cone", Access::write,
                ResourceDesc{Format::rgba16_float, SizeRule::render}.with(finite_values())}};
    const double px = double(s.width) * s.height;
    d.work = {{"march_steps", g.ssdo ? px * g.ssdo_directions * g.ssdo_steps : 0.0}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    ScreenSpacePush push{{g.ssdo_radius, g.ssdo_thickness, 0.0f, 0.0f},
                         {g.ssdo_directions, g.ssdo_steps, g.ssdo ? 1u : 0u, ctx.settings.nan_guards ? 1u : 0u}};
    record_compute(ctx, {.shader = "ssdo.comp",
                         .images = {{kSsdoBindPosition, "gbuffer_position"},
                                    {kSsdoBindNormal, "gbuffer_normal"},
                                    {kSsdoBindAlbedo, "gbuffer_albedo"},
                                    {kSsdoBindLight, "ssdo_local_light"},
                                    {kSsdoBindCone, "ssdo_cone"}},
                         .groups_x = div_up(ctx.width("ssdo_local_light"), kSsGroup),
                         .groups_y = div_up(ctx.height("ssdo_local_light"), kSsGroup),
                         .push = &push,
                         .push_bytes = sizeof(push)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_ssdo_pass() { return std::make_unique<SsdoPass>(); }

}  // namespace gib
