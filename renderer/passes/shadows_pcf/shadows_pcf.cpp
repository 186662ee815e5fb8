#include "renderer/passes/shadows_pcf/shadows_pcf.h"

#include "renderer/passes/shadows_pcf/shadows_pcf_shared.h"
#include "renderer/passes/shadow_cascades.h"

namespace gib {
namespace {

class ShadowsPcfPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<SunShadowParams>();
    PassDecl d;
    d.name = "shadows_pcf";
    d.needs = Feature::sun;
    d.slots = shadow_filter_slots("shadow_pcf");
    d.work = {{"taps", double(s.width) * s.height * g.shadow_taps}};
    return d;
  }
  void record(RecordContext& ctx) override { record_shadow_filter(ctx, "shadows_pcf.comp", "shadow_pcf"); }
};

}  // namespace

std::unique_ptr<Pass> make_shadows_pcf_pass() { return std::make_unique<ShadowsPcfPass>(); }

}  // namespace gib
