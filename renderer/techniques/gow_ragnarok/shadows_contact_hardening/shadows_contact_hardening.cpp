#include "renderer/techniques/gow_ragnarok/shadows_contact_hardening/shadows_contact_hardening.h"

#include "renderer/techniques/gow_ragnarok/shadows_contact_hardening/shadows_contact_hardening_shared.h"
#include "renderer/passes/shadow_cascades.h"

namespace gib {
namespace {

class ShadowsContactHardeningPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<SunShadowParams>();
    PassDecl d;
    d.name = "shadows_contact_hardening";
    d.needs = Feature::sun;
    d.slots = shadow_filter_slots("shadow_contact_hardening");
    d.work = {{"ray_steps", double(s.width) * s.height * g.shadow_taps * g.shadow_march_steps}};
    return d;
  }
  void record(RecordContext& ctx) override { record_shadow_filter(ctx, "shadows_contact_hardening.comp", "shadow_contact_hardening"); }
};

}  // namespace

std::unique_ptr<Pass> make_shadows_contact_hardening_pass() { return std::make_unique<ShadowsContactHardeningPass>(); }

}  // namespace gib
