#include "renderer/techniques/gow_ragnarok/reflections_rt_cubemap/reflections_rt_cubemap.h"

#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/techniques/gow_ragnarok/reflections_rt_cubemap/reflections_rt_cubemap_shared.h"

namespace gib {
namespace {

class ReflectionsRtCubemapPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    ResourceDesc stats{Format::buffer, SizeRule::buffer};
    stats.bytes = 4 * glsl::kReflStatWords;
    PassDecl d;
    d.name = "reflections_rt_cubemap";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    d.needs = Feature::glossy;
    d.slots = {{"vbuffer", Access::read},
               {"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_albedo", Access::read},
               {"reflection_cubemap", Access::read},
               {"reflection_trace", Access::write,
                ResourceDesc{Format::rgba32_float, SizeRule::half}.with(non_negative_values())},
               {"reflection_stats", Access::write, stats}};
    // The cube map alone reads no screen: direct_light is an input of the ray-traced mode only.
    if (g.reflection_mode == uint32_t(ReflectionMode::rt_cubemap)) d.slots.push_back({"direct_light", Access::read});
    const double rays = double(s.width / 2) * (s.height / 2);
    d.work = {{"rays", rays}, {"ssr_steps", g.reflection_mode ? rays * g.ssr_steps : 0.0}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    const bool rt = g.reflection_mode == uint32_t(ReflectionMode::rt_cubemap);
    ReflTracePush push{ctx.frame, g.cubemap_size, g.ssr_steps, g.ssr_thickness, g.reflection_distance, 0, 0, 0};
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("reflection_stats"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    std::vector<ImageBinding> images = {{kReflTraceBindVbuffer, "vbuffer"},
                                        {kReflTraceBindPosition, "gbuffer_position"},
                                        {kReflTraceBindNormal, "gbuffer_normal"},
                                        {kReflTraceBindAlbedo, "gbuffer_albedo"},
                                        {kReflTraceBindCubemap, "reflection_cubemap"},
                                        {kReflTraceBindOut, "reflection_trace"}};
    // The cube-map mode binds the cube map in the screen's place (the shader never reads it).
    images.push_back({kReflTraceBindScreen, rt ? "direct_light" : "reflection_cubemap"});
    const Image& out = ctx.image("reflection_trace");
    record_compute(ctx, {.shader = "reflections_rt_cubemap.comp",
                         .images = images,
                         .groups_x = div_up(out.width(), kReflTraceGroup),
                         .groups_y = div_up(out.height(), kReflTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kReflTraceSpecMode, g.reflection_mode}},
                         .buffers = {{kReflTraceBindStats, "reflection_stats"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_reflections_rt_cubemap_pass() { return std::make_unique<ReflectionsRtCubemapPass>(); }

}  // namespace gib
