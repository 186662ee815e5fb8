#include "renderer/techniques/probe_volume/probe_select/probe_select.h"

#include "renderer/techniques/probe_volume/probe_select/probe_select_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class ProbeSelectPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
    check_pv_settings(p);
    PassDecl d;
    d.name = "probe_select";
    ResourceDesc state{Format::buffer, SizeRule::buffer};
    state.bytes = pv_state_bytes(p);
    state.persistent = true;
    ResourceDesc selection{Format::buffer, SizeRule::buffer};
    selection.bytes = pv_selection_bytes(p);
    d.slots = {{"probe_state", Access::read_write, state}, {"probe_selection", Access::write, selection}};
    d.work = {{"probes", double(pv_probe_count(p))}, {"budget", double(p.probe_budget)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    // probe_state is persistent: the executor zeroes it when it creates it.
    PvSelectPush push{make_pv_params(ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "probe_select.comp",
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kPvSelectBindState, "probe_state"}, {kPvSelectBindSelection, "probe_selection"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_select_pass() { return std::make_unique<ProbeSelectPass>(); }

}  // namespace gib
