#include "renderer/techniques/reference/path_trace/path_trace.h"

#include "renderer/techniques/reference/path_trace/path_trace_shared.h"
#include "renderer/techniques/reference/reference.h"

namespace gib {
namespace {

class PathTracePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "path_trace";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    ResourceDesc sum{Format::rgba32_float, SizeRule::render};
    sum.persistent = true;
    sum.values = non_negative_values();  // rgb radiance sums, a sample count
    d.slots = {{"pt_radiance_sum", Access::read_write, sum},
               {"pt_direct_sum", Access::read_write, sum},
               {"pt_indirect_sum", Access::read_write, sum},
               {"pt_reflection_sum", Access::read_write, sum}};
    d.work = {{"camera_samples", double(s.width) * s.height * s.params<ReferenceSettings>().spp_per_frame}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    SceneFeatures f = ctx.scene.features();
    const DebugSettings& dbg = ctx.settings.debug;
    const ReferenceSettings& r = ctx.settings.params<ReferenceSettings>();
    PathTracePush push{r.spp_per_frame,
                       r.max_bounces,
                       ctx.frame * r.spp_per_frame,
                       ctx.settings.nan_guards ? 1u : 0u,
                       dbg.injects(3, ctx.frame) ? 1u : 0u,
                       dbg.inject_x,
                       dbg.inject_y,
                       r.glossy_masking};
    static_assert(sizeof(push) == 32, "PathTracePush must match path_trace.comp's push block");
    record_compute(ctx, {.shader = "path_trace.comp",
                         .images = {{kPathTraceBindRadiance, "pt_radiance_sum"},
                                    {kPathTraceBindDirect, "pt_direct_sum"},
                                    {kPathTraceBindIndirect, "pt_indirect_sum"},
                                    {kPathTraceBindReflection, "pt_reflection_sum"}},
                         .groups_x = div_up(ctx.width("pt_radiance_sum"), kPathTraceGroup),
                         .groups_y = div_up(ctx.height("pt_radiance_sum"), kPathTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kPathTraceSpecSun, f.has(Feature::sun)},
                                            {kPathTraceSpecLocal, f.has(Feature::local_lights)},
                                            {kPathTraceSpecAlpha, f.has(Feature::alpha_tested)}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_path_trace_pass() { return std::make_unique<PathTracePass>(); }

}  // namespace gib
