#include "renderer/techniques/gow_ragnarok/reflections_resolve/reflections_resolve.h"

#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/techniques/gow_ragnarok/reflections_resolve/reflections_resolve_shared.h"

namespace gib {
namespace {

class ReflectionsResolvePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    ResourceDesc out{Format::rgba32_float, SizeRule::render};
    out.persistent = true;
    out.values = non_negative_values();
    PassDecl d;
    d.name = "reflections_resolve";
    d.needs = Feature::glossy;
    d.slots = {{"reflection_trace", Access::read},
               {"gbuffer_position", Access::read},
               {"reflection", Access::write, out},
               {"reflection", Access::read_prev}};
    d.work = {{"pixels", double(s.width) * s.height}, {"history_frames", double(g.reflection_history)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    ReflResolvePush push{float(g.reflection_history), ctx.frame > 0 ? 1u : 0u, ctx.settings.nan_guards ? 1u : 0u, 0};
    record_compute(ctx, {.shader = "reflections_resolve.comp",
                         .images = {{kReflResolveBindTrace, "reflection_trace"},
                                    {kReflResolveBindPosition, "gbuffer_position"},
                                    {kReflResolveBindHistory, "reflection", true},
                                    {kReflResolveBindOut, "reflection"}},
                         .groups_x = div_up(ctx.width("reflection"), kReflResolveGroup),
                         .groups_y = div_up(ctx.height("reflection"), kReflResolveGroup),
                         .push = &push,
                         .push_bytes = sizeof(push)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_reflections_resolve_pass() { return std::make_unique<ReflectionsResolvePass>(); }

}  // namespace gib
