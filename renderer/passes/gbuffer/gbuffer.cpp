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
    d.slots = {{"vbuffer", Access::read},
               {"gbuffer_albedo", Access::write, {Format::rgba16_float, SizeRule::render}},
               {"gbuffer_normal", Access::write, normal},
               {"gbuffer_position", Access::write, position},
               {"gbuffer_emissive", Access::write, {Format::rgba16_float, SizeRule::render}}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    record_compute(ctx, {.shader = "gbuffer.comp",
                         .images = {{kGbufferBindVbuffer, "vbuffer"},
                                    {kGbufferBindAlbedo, "gbuffer_albedo"},
                                    {kGbufferBindNormal, "gbuffer_normal"},
                                    {kGbufferBindPosition, "gbuffer_position"},
                                    {kGbufferBindEmissive, "gbuffer_emissive"}},
                         .groups_x = div_up(ctx.width("vbuffer"), kGbufferGroup),
                         .groups_y = div_up(ctx.height("vbuffer"), kGbufferGroup)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_gbuffer_pass() { return std::make_unique<GbufferPass>(); }

}  // namespace gib
