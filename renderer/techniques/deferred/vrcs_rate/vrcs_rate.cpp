#include "renderer/techniques/deferred/vrcs_rate/vrcs_rate.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/vrcs_rate/vrcs_rate_shared.h"

namespace gib {
namespace {

class VrcsRatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "vrcs_rate";
    d.slots = {{"vbuffer", Access::read},
               {"vis_tangent_frame", Access::read},
               {"vrcs_rates", Access::write,
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, vrcs_rate_words(s.width, s.height) * 4}}};
    // Last frame's luminance exists (deferred_lighting writes vrcs_luma) only with VRCS on in
    // the tiled lighting; without VRCS nothing reads vrcs_rates and the graph culls this pass.
    const DeferredSettings& ds = s.params<DeferredSettings>();
    if (ds.vrcs && ds.tile_classification) d.slots.push_back({"vrcs_luma", Access::read_prev});
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeferredSettings& ds = ctx.settings.params<DeferredSettings>();
    const uint32_t w = ctx.width("vbuffer"), h = ctx.height("vbuffer");
    if (!ds.tile_classification)
      throw GraphError("vrcs_rate: vrcs 1 needs tile_classification 1 (its rate reads last frame's tiled lighting)");
    VrcsPush push{ds.vrcs_threshold, ds.vrcs_edges ? 1u : 0u, ds.vrcs_force, ctx.frame > 0 ? 1u : 0u,
                  div_up(w, kVrcsTile), 0, 0, 0};
    static_assert(sizeof(push) == 32, "VrcsPush must match vrcs_rate.comp's push block");
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("vrcs_rates"), 0u);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    record_compute(ctx, {.shader = "vrcs_rate.comp",
                         .images = {{kVrcsBindVbuffer, "vbuffer"},
                                    {kVrcsBindTangentFrame, "vis_tangent_frame"},
                                    {kVrcsBindPrevLuma, "vrcs_luma", true}},
                         .groups_x = div_up(w, kVrcsTile),
                         .groups_y = div_up(h, kVrcsTile),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kVrcsBindRates, "vrcs_rates"}}});
  }
};

}  // namespace

uint64_t vrcs_rate_words(uint32_t width, uint32_t height) {
  return glsl::kVrcsHeader + uint64_t(div_up(width, glsl::kVrcsTile)) * div_up(height, glsl::kVrcsTile);
}

std::unique_ptr<Pass> make_vrcs_rate_pass() { return std::make_unique<VrcsRatePass>(); }

}  // namespace gib
