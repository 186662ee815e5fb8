#include "renderer/techniques/gow_ragnarok/direct_aov/direct_aov.h"

#include "renderer/techniques/gow_ragnarok/direct_aov/direct_aov_shared.h"
#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"

namespace gib {
namespace {

class DirectAovPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    PassDecl d;
    d.name = "direct_aov";
    if (!s.params<GowRagnarokSettings>().ss_combined) return d;  // the separate ssgi pass writes it: culled
    d.slots = {{"direct_light", Access::read},
               {"gow_direct", Access::write,
                ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())}};
    if (gow_unshadowed_local_lights(scene, s)) d.slots.push_back({"ssdo_local_light", Access::read});
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const bool local = gow_unshadowed_local_lights(ctx.scene, ctx.settings);
    // Without local lights the local binding (sampled, so any float format fits) holds
    // direct_light's image, unread.
    record_compute(ctx, {.shader = "direct_aov.comp",
                         .images = {{kDirectAovBindDirect, "direct_light"},
                                    {kDirectAovBindLocal, local ? "ssdo_local_light" : "direct_light", false, true},
                                    {kDirectAovBindOut, "gow_direct"}},
                         .groups_x = div_up(ctx.width("gow_direct"), kDirectAovGroup),
                         .groups_y = div_up(ctx.height("gow_direct"), kDirectAovGroup),
                         .spec_constants = {{kDirectAovSpecLocal, local}},
                         .scene = false});
  }
};

}  // namespace

std::unique_ptr<Pass> make_direct_aov_pass() { return std::make_unique<DirectAovPass>(); }

}  // namespace gib
