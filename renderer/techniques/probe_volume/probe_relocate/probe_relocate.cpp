#include "renderer/techniques/probe_volume/probe_relocate/probe_relocate.h"

#include "renderer/techniques/probe_volume/probe_relocate/probe_relocate_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeRelocatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "probe_relocate";
    d.slots = {{"probe_selection", Access::read}, {"probe_gb_depth", Access::read}, {"probe_state", Access::read_write}};
    d.work = {{"probes", double(s.params<ProbeVolumeSettings>().probe_budget)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    PvRelocatePush push{make_pv_params(ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "probe_relocate.comp",
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .scene = true,
                         .buffers = {{kPvRelocateBindState, "probe_state"},
                                     {kPvRelocateBindSelection, "probe_selection"},
                                     {kPvRelocateBindDepth, "probe_gb_depth"}},
                         .indirect = "probe_selection",
                         .indirect_offset = offsetof(PvSelection, traced_args)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_relocate_pass() { return std::make_unique<ProbeRelocatePass>(); }

}  // namespace gib
