#include "renderer/techniques/probe_volume/probe_classify/probe_classify.h"

#include "renderer/techniques/probe_volume/probe_classify/probe_classify_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeClassifyPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "probe_classify";
    d.needs = Feature::indoor_volumes;
    d.slots = {{"probe_selection", Access::read}, {"probe_state", Access::read_write}};
    d.work = {{"probes", double(s.params<ProbeVolumeSettings>().probe_budget)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const ProbeVolumeSettings& p = ctx.settings.params<ProbeVolumeSettings>();
    PvClassifyPush push{make_pv_params(ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "probe_classify.comp",
                         .groups_x = div_up(p.probe_budget, kPvClassifyGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kPvClassifyBindState, "probe_state"}, {kPvClassifyBindSelection, "probe_selection"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_classify_pass() { return std::make_unique<ProbeClassifyPass>(); }

}  // namespace gib
