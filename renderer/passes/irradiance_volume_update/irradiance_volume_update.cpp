#include "renderer/passes/irradiance_volume_update/irradiance_volume_update.h"

#include "renderer/passes/irradiance_volume_update/irradiance_volume_update_shared.h"
#include "renderer/techniques/radiance_cache_params.h"

namespace gib {
namespace {

constexpr uint32_t kProbesPerCascade = glsl::kProbeGridDim * glsl::kProbeGridDim * glsl::kProbeGridDim;

class IrradianceVolumeUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "irradiance_volume_update";
    ResourceDesc irr{Format::r32_uint, SizeRule::fixed, glsl::kProbeAtlasWidth,
                     glsl::kProbeAtlasRowsPerCascade * s.rc.cascades};
    irr.persistent = true;
    ResourceDesc vis = irr;
    vis.format = Format::rg16_float;
    d.slots = {{"probe_hits", Access::read},
               {"rc_cells", Access::read},
               {"probe_irradiance", Access::write, irr},
               {"probe_visibility", Access::write, vis},
               {"probe_irradiance", Access::read_prev},
               {"probe_visibility", Access::read_prev}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    // Last frame's writes of the atlas (and earlier readers of this copy) before the copy.
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.begin_label("irradiance_volume_update/copy");
    ctx.cmd.copy(ctx.prev_image("probe_irradiance"), ctx.image("probe_irradiance"));
    ctx.cmd.copy(ctx.prev_image("probe_visibility"), ctx.image("probe_visibility"));
    ctx.cmd.end_label();
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    ctx.cmd.begin_label("irradiance_volume_update/convolve");
    IvPush push{make_rc_params(ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "irradiance_volume_update.comp",
                         .images = {{kIvBindPrevIrradiance, "probe_irradiance", true},
                                    {kIvBindPrevVisibility, "probe_visibility", true},
                                    {kIvBindIrradiance, "probe_irradiance"},
                                    {kIvBindVisibility, "probe_visibility"}},
                         .groups_x = kProbesPerCascade,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kIvSpecCacheFallback, 1}},
                         .buffers = {{kIvBindHits, "probe_hits"}, {kIvBindCells, "rc_cells"}}});
    ctx.cmd.end_label();
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_volume_update_pass() { return std::make_unique<IrradianceVolumeUpdatePass>(); }

}  // namespace gib
