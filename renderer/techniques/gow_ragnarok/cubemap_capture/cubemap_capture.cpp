#include "renderer/techniques/gow_ragnarok/cubemap_capture/cubemap_capture.h"

#include "renderer/techniques/gow_ragnarok/cubemap_capture/cubemap_capture_shared.h"
#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"

namespace gib {
namespace {

class CubemapCapturePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    ResourceDesc sum{Format::rgba32_float, SizeRule::fixed};
    sum.width = 6 * g.cubemap_size;
    sum.height = g.cubemap_size;
    sum.persistent = true;
    sum.values = non_negative_values();
    PassDecl d;
    d.name = "cubemap_capture";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    d.needs = Feature::glossy;
    d.slots = {{"reflection_cubemap", Access::read_write, sum}};
    d.work = {{"paths", 6.0 * g.cubemap_size * g.cubemap_size}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    CubemapCapturePush push{g.cubemap_size, g.cubemap_bounces, ctx.frame, ctx.settings.nan_guards ? 1u : 0u};
    SceneFeatures f = ctx.scene.features();
    record_compute(ctx, {.shader = "cubemap_capture.comp",
                         .images = {{kCubemapCaptureBindSum, "reflection_cubemap"}},
                         .groups_x = div_up(6 * g.cubemap_size, kCubemapCaptureGroup),
                         .groups_y = div_up(g.cubemap_size, kCubemapCaptureGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{0, f.has(Feature::sun)}, {1, f.has(Feature::local_lights)}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_cubemap_capture_pass() { return std::make_unique<CubemapCapturePass>(); }

}  // namespace gib
