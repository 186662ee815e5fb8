#include "renderer/passes/visibility/visibility.h"

namespace gib {
namespace {

class VisibilityPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "visibility";
    d.kind = PassKind::graphics;
    d.slots = {{"vbuffer", Access::write, {Format::rg32_uint, SizeRule::render}},
               {"depth", Access::write, ResourceDesc{Format::d32_float, SizeRule::render}.with(unit_values())}};
    return d;
  }

  void record(RecordContext& ctx) override {
    GraphicsPipelineDesc desc;
    desc.vertex_shader = "visibility.vert";
    desc.fragment_shader = "visibility.frag";
    desc.bindings = scene_bindings();
    desc.color_formats = {Format::rg32_uint};
    desc.depth = true;
    auto pipeline = ctx.gpu.graphics_pipeline(desc);
    const Image* colors[] = {&ctx.image("vbuffer")};
    const float clear[4] = {0, 0, 0, 0};
    ctx.cmd.begin_rendering(colors, &ctx.image("depth"), clear);
    auto binds = ctx.scene_gpu.binds();
    ctx.cmd.bind(*pipeline, binds);
    ctx.cmd.draw(ctx.scene_gpu.triangle_count * 3);
    ctx.cmd.end_rendering();
  }
};

}  // namespace

std::unique_ptr<Pass> make_visibility_pass() { return std::make_unique<VisibilityPass>(); }

}  // namespace gib
