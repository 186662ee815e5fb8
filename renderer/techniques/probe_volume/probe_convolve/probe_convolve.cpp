#include "renderer/techniques/probe_volume/probe_convolve/probe_convolve.h"

#include "renderer/techniques/probe_volume/probe_convolve/probe_convolve_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeConvolvePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    const uint64_t probes = pv_probe_count(p);
    PassDecl d;
    d.name = "probe_convolve";
    auto buffer = [](uint64_t bytes) { return pv_buffer(bytes, true); };
    d.slots = {{"probe_selection", Access::read},
               {"probe_gb_material", Access::read},
               {"probe_gb_depth", Access::read},
               {"probe_texel_radiance", Access::read},
               {"probe_texel_local", Access::read},
               {"probe_state", Access::read_write},
               {"probe_irradiance", Access::read_write, buffer(probes * glsl::kPvIrradianceTexels * 8)},
               {"probe_radiance", Access::read_write, buffer(probes * glsl::kPvRadianceTexels * 8)},
               {"probe_visibility", Access::read_write, buffer(probes * glsl::kPvRadianceTexels * 2)}};
    d.work = {{"probes", double(p.probe_budget)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    // The probe buffers are persistent: the executor zeroes them when it creates them.
    PvConvolvePush push{make_pv_params(ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "probe_convolve.comp",
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kPvConvolveSpecSky, ctx.scene.features().has(Feature::sky)}},
                         .buffers = {{kPvConvolveBindState, "probe_state"},
                                     {kPvConvolveBindSelection, "probe_selection"},
                                     {kPvConvolveBindMaterial, "probe_gb_material"},
                                     {kPvConvolveBindDepth, "probe_gb_depth"},
                                     {kPvConvolveBindRadianceIn, "probe_texel_radiance"},
                                     {kPvConvolveBindLocal, "probe_texel_local"},
                                     {kPvConvolveBindIrradiance, "probe_irradiance"},
                                     {kPvConvolveBindRadiance, "probe_radiance"},
                                     {kPvConvolveBindVisibility, "probe_visibility"}},
                         .indirect = "probe_selection",
                         .indirect_offset = offsetof(PvSelection, all_args)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_convolve_pass() { return std::make_unique<ProbeConvolvePass>(); }

}  // namespace gib
