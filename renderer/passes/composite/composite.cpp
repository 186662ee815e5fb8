#include "renderer/passes/composite/composite.h"

#include "renderer/passes/composite/composite_shared.h"

namespace gib {
namespace {

class CompositePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "composite";
    d.slots = {{"direct_light", Access::read},
               {"gbuffer_albedo", Access::read},
               {"gi_irradiance", Access::read},
               {"gi_direct_irradiance", Access::read}};
    for (Slot& s : composite_output_slots()) d.slots.push_back(std::move(s));
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    record_compute(ctx, {.shader = "composite.comp",
                         .images = {{kCompositeBindDirect, "direct_light"},
                                    {kCompositeBindAlbedo, "gbuffer_albedo"},
                                    {kCompositeBindIrradiance, "gi_irradiance"},
                                    {kCompositeBindColor, "final_color"},
                                    {kCompositeBindIndirect, "indirect_diffuse"},
                                    {kCompositeBindGiDirect, "gi_direct_irradiance"},
                                    {kCompositeBindDirectOut, "direct_radiance"}},
                         .groups_x = div_up(ctx.width("final_color"), kCompositeGroup),
                         .groups_y = div_up(ctx.height("final_color"), kCompositeGroup),
                         .scene = false});
  }
};

}  // namespace

std::vector<Slot> composite_output_slots() {
  ResourceDesc color{Format::rgba32_float, SizeRule::render};
  color.persistent = true;
  color.values = non_negative_values();
  const ResourceDesc aov = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
  return {{"final_color", Access::write, color},
          {"indirect_diffuse", Access::write, aov},
          {"direct_radiance", Access::write, aov}};
}

std::unique_ptr<Pass> make_composite_pass() { return std::make_unique<CompositePass>(); }

}  // namespace gib
