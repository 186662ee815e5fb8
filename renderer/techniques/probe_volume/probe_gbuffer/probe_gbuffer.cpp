#include "renderer/techniques/probe_volume/probe_gbuffer/probe_gbuffer.h"

#include "renderer/techniques/probe_volume/probe_gbuffer/probe_gbuffer_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeGbufferPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    const uint64_t texels = uint64_t(pv_probe_count(p)) * glsl::kPvGbufferTexels;
    PassDecl d;
    d.name = "probe_gbuffer";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    auto buffer = [](uint64_t bytes) { return pv_buffer(bytes, true); };
    d.slots = {{"probe_selection", Access::read},
               {"probe_state", Access::read_write},
               {"probe_gb_material", Access::read_write, buffer(texels * 8)},
               {"probe_gb_normal", Access::read_write, buffer(texels * 4)},
               {"probe_gb_depth", Access::read_write, buffer(texels * 2)}};
    // Upper bound: every traced probe at full resolution (new probes trace a quarter).
    d.work = {{"rays", double(p.probe_budget) * glsl::kPvGbufferTexels}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    PvGbufferPush push{make_pv_params(ctx.settings, ctx.frame)};
    const SceneFeatures f = ctx.scene.features();
    record_compute(ctx, {.shader = "probe_gbuffer.comp",
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kPvGbufferSpecAlpha, f.has(Feature::alpha_tested)},
                                            {kPvGbufferSpecSun, f.has(Feature::sun)}},
                         .buffers = {{kPvGbufferBindState, "probe_state"},
                                     {kPvGbufferBindSelection, "probe_selection"},
                                     {kPvGbufferBindMaterial, "probe_gb_material"},
                                     {kPvGbufferBindNormal, "probe_gb_normal"},
                                     {kPvGbufferBindDepth, "probe_gb_depth"}},
                         .indirect = "probe_selection",
                         .indirect_offset = offsetof(PvSelection, traced_args)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_gbuffer_pass() { return std::make_unique<ProbeGbufferPass>(); }

}  // namespace gib
