#include "renderer/passes/gbuffer/gbuffer.h"

#include "renderer/passes/gbuffer/gbuffer_shared.h"

namespace gib {
namespace {

class GbufferPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "gbuffer";
    // Normal and position are persistent so temporal passes may read last frame's copy
    // (read_prev): the graph then keeps two and ping-pongs them; otherwise they cost one.
    ResourceDesc normal{Format::rgba16_float, SizeRule::render}, position{Format::rgba32_float, SizeRule::render};
    normal.persistent = position.persistent = true;
    normal.values = unit_values().allow_negative(kChannelsRgb);             // xyz unit normal, w roughness
    position.values = non_negative_values().allow_negative(kChannelsRgb);  // xyz world position, w distance
    d.slots = {{"vbuffer", Access::read},
               {"gbuffer_albedo", Access::write, ResourceDesc{Format::rgba16_float, SizeRule::render}.with(unit_values())},
               {"gbuffer_normal", Access::write, normal},
               {"gbuffer_position", Access::write, position},
               {"gbuffer_emissive", Access::write,  // rgb emission, a translucency
                ResourceDesc{Format::rgba16_float, SizeRule::render}.with(non_negative_values())}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DebugSettings& dbg = ctx.settings.debug;
    GbufferPush push{ctx.settings.nan_guards ? 1u : 0u, dbg.injects(1, ctx.frame) ? 1u : 0u, dbg.inject_x,
                     dbg.inject_y};
    static_assert(sizeof(push) == 16, "GbufferPush must match gbuffer.comp's push block");
    record_compute(ctx, {.shader = "gbuffer.comp",
                         .images = {{kGbufferBindVbuffer, "vbuffer"},
                                    {kGbufferBindAlbedo, "gbuffer_albedo"},
                                    {kGbufferBindNormal, "gbuffer_normal"},
                                    {kGbufferBindPosition, "gbuffer_position"},
                                    {kGbufferBindEmissive, "gbuffer_emissive"}},
                         .groups_x = div_up(ctx.width("vbuffer"), kGbufferGroup),
                         .groups_y = div_up(ctx.height("vbuffer"), kGbufferGroup),
                         .push = &push,
                         .push_bytes = sizeof(push)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_gbuffer_pass() { return std::make_unique<GbufferPass>(); }

}  // namespace gib
