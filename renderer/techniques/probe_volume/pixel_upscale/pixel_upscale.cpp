#include "renderer/techniques/probe_volume/pixel_upscale/pixel_upscale.h"

#include "renderer/techniques/probe_volume/pixel_upscale/pixel_upscale_shared.h"
#include "renderer/techniques/probe_volume/probe_volume_params.h"

namespace gib {
namespace {

class PixelUpscalePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "pixel_upscale";
    const ResourceDesc out = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
    d.slots = {{"pixel_gi_y", Access::read},
               {"pixel_gi_c", Access::read},
               {"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_emissive", Access::read},
               {"gi_irradiance", Access::write, out},
               {"gi_direct_irradiance", Access::write, out}};
    d.work = {{"pixels", double(s.width) * s.height}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    PvUpscalePush push{make_pv_params(ctx.settings, ctx.frame)};
    const Image& out = ctx.image("gi_irradiance");
    record_compute(ctx, {.shader = "pixel_upscale.comp",
                         .images = {{kPvUpscaleBindPosition, "gbuffer_position"},
                                    {kPvUpscaleBindNormal, "gbuffer_normal"},
                                    {kPvUpscaleBindEmissive, "gbuffer_emissive"},
                                    {kPvUpscaleBindGiY, "pixel_gi_y"},
                                    {kPvUpscaleBindGiC, "pixel_gi_c"},
                                    {kPvUpscaleBindIrradiance, "gi_irradiance"},
                                    {kPvUpscaleBindDirect, "gi_direct_irradiance"}},
                         .groups_x = div_up(out.width(), kPvUpscaleGroup),
                         .groups_y = div_up(out.height(), kPvUpscaleGroup),
                         .push = &push,
                         .push_bytes = sizeof(push)});
  }
};

}  // namespace

std::unique_ptr<Pass> make_pixel_upscale_pass() { return std::make_unique<PixelUpscalePass>(); }

}  // namespace gib
