#include "renderer/techniques/voxel_clipmap/irradiance_shade/irradiance_shade.h"

#include "renderer/techniques/voxel_clipmap/irradiance_shade/irradiance_shade_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class IrradianceShadePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    const ResourceDesc out = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
    PassDecl d;
    d.name = "irradiance_shade";
    d.slots = {{"voxel_clip_state", Access::read},      {"irradiance_x", Access::read},
               {"irradiance_y", Access::read},          {"irradiance_z", Access::read},
               {"irradiance_cell_state", Access::read}, {"scene_voxel_data", Access::read},
               {"scene_voxel_third", Access::read},        {"irradiance_cell_vis", Access::read},
               {"gbuffer_normal", Access::read},        {"gbuffer_position", Access::read},
               {"direct_light", Access::read},
               {"gi_irradiance", Access::write, out},   {"gi_direct_irradiance", Access::write, out}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    IrrShadePush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "irradiance_shade.comp",
                         .images = {{kIrrShadeBindNormal, "gbuffer_normal"},
                                    {kIrrShadeBindPosition, "gbuffer_position"},
                                    {kIrrShadeBindDirect, "direct_light"},
                                    {kIrrShadeBindBounce, "gi_irradiance"},
                                    {kIrrShadeBindSky, "gi_direct_irradiance"}},
                         .groups_x = div_up(ctx.width("gi_irradiance"), kIrrShadeGroup),
                         .groups_y = div_up(ctx.height("gi_irradiance"), kIrrShadeGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kIrrShadeBindState, "voxel_clip_state"},
                                     {kIrrShadeBindX, "irradiance_x"},
                                     {kIrrShadeBindY, "irradiance_y"},
                                     {kIrrShadeBindZ, "irradiance_z"},
                                     {kIrrShadeBindCells, "irradiance_cell_state"},
                                     {kIrrShadeBindVoxels, "scene_voxel_data"},
                                     {kIrrShadeBindThird, "scene_voxel_third"},
                                     {kIrrShadeBindVis, "irradiance_cell_vis"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_shade_pass() { return std::make_unique<IrradianceShadePass>(); }

}  // namespace gib
