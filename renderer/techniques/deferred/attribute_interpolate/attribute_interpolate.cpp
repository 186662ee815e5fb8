#include "renderer/techniques/deferred/attribute_interpolate/attribute_interpolate.h"

#include "renderer/techniques/deferred/attribute_interpolate/attribute_interpolate_shared.h"

namespace gib {
namespace {

class AttributeInterpolatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "attribute_interpolate";
    d.slots = {{"vbuffer", Access::read},
               {"vis_bary", Access::write, ResourceDesc{Format::rg16_float, SizeRule::render}.with(finite_values())},
               {"vis_bary_deriv", Access::write, ResourceDesc{Format::rgba16_uint, SizeRule::render}},
               {"vis_tangent_frame", Access::write,
                ResourceDesc{Format::rgba16_float, SizeRule::render}.with(finite_values())}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    AttrPush push{ctx.settings.nan_guards ? 1u : 0u, 0, 0, 0};
    static_assert(sizeof(push) == 16, "AttrPush must match attribute_interpolate.comp's push block");
    record_compute(ctx, {.shader = "attribute_interpolate.comp",
                         .images = {{kAttrBindVbuffer, "vbuffer"},
                                    {kAttrBindBary, "vis_bary"},
                                    {kAttrBindBaryDeriv, "vis_bary_deriv"},
                                    {kAttrBindTangentFrame, "vis_tangent_frame"}},
                         .groups_x = div_up(ctx.width("vbuffer"), kAttrGroup),
                         .groups_y = div_up(ctx.height("vbuffer"), kAttrGroup),
                         .push = &push,
                         .push_bytes = sizeof(push)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_attribute_interpolate_pass() { return std::make_unique<AttributeInterpolatePass>(); }

}  // namespace gib
