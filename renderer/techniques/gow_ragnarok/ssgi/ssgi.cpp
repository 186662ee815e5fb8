#include "renderer/techniques/gow_ragnarok/ssgi/ssgi.h"

#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/techniques/gow_ragnarok/ssgi/ssgi_shared.h"

namespace gib {
namespace {

class SsgiPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    const ResourceDesc out = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
    PassDecl d;
    d.name = "ssgi";
    if (g.ss_combined) return d;  // ssdo_ssgi runs: nothing to write, culled
    d.slots = {{"gbuffer_position", Access::read}, {"gbuffer_normal", Access::read},
               {"gbuffer_albedo", Access::read},   {"gbuffer_emissive", Access::read},
               {"direct_light", Access::read},     {"gow_direct", Access::write, out},
               {"ssgi_indirect", Access::write, out}, {"gow_radiance", Access::write, out}};
    if (gow_unshadowed_local_lights(scene, s)) d.slots.push_back({"ssdo_local_light", Access::read});
    const double px = double(s.width) * s.height;
    d.work = {{"march_steps", g.ssgi ? px * g.ssgi_directions * g.ssgi_steps : 0.0}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    const bool local = gow_unshadowed_local_lights(ctx.scene, ctx.settings);
    ScreenSpacePush push{{g.ssgi_radius, g.ssgi_thickness, 0.0f, 0.0f},
                         {g.ssgi_directions, g.ssgi_steps, g.ssgi ? 1u : 0u, ctx.settings.nan_guards ? 1u : 0u}};
    record_compute(ctx, {.shader = "ssgi.comp",
                         .images = {{kSsgiBindPosition, "gbuffer_position"},
                                    {kSsgiBindNormal, "gbuffer_normal"},
                                    {kSsgiBindAlbedo, "gbuffer_albedo"},
                                    {kSsgiBindEmissive, "gbuffer_emissive"},
                                    {kSsgiBindDirect, "direct_light"},
                                    // Without local light the binding holds direct_light, unread.
                                    {kSsgiBindLocal, local ? "ssdo_local_light" : "direct_light"},
                                    {kSsgiBindOutDirect, "gow_direct"},
                                    {kSsgiBindOutIndirect, "ssgi_indirect"},
                                    {kSsgiBindOutRadiance, "gow_radiance"}},
                         .groups_x = div_up(ctx.width("gow_radiance"), kSsGroup),
                         .groups_y = div_up(ctx.height("gow_radiance"), kSsGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kSsgiSpecLocal, local}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_ssgi_pass() { return std::make_unique<SsgiPass>(); }

}  // namespace gib
