#include "renderer/techniques/voxel_clipmap/irradiance_relight/irradiance_relight.h"

#include "renderer/techniques/voxel_clipmap/irradiance_relight/irradiance_relight_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class IrradianceRelightPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "irradiance_relight";
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"irradiance_queue", Access::read},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"irradiance_x", Access::read_write, vc_cube_desc(p)},
               {"irradiance_y", Access::read_write, vc_cube_desc(p)},
               {"irradiance_z", Access::read_write, vc_cube_desc(p)},
               {"irradiance_cell_state", Access::read_write, vc_cell_state_desc(p)},
               {"irradiance_cell_vis", Access::read_write, vc_cell_vis_desc(p)}};
    d.work = {{"rays", double(vc_queue_capacity(p)) * p.rays_per_cell}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    IrrRelightPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "irradiance_relight.comp",
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kIrrRelightSpecRays, ctx.settings.params<VoxelClipmapSettings>().rays_per_cell}},
                         .buffers = {{kIrrRelightBindState, "voxel_clip_state"},
                                     {kIrrRelightBindVoxels, "scene_voxel_data"},
                                     {kIrrRelightBindQueue, "irradiance_queue"},
                                     {kIrrRelightBindX, "irradiance_x"},
                                     {kIrrRelightBindY, "irradiance_y"},
                                     {kIrrRelightBindZ, "irradiance_z"},
                                     {kIrrRelightBindCells, "irradiance_cell_state"},
                                     {kIrrRelightBindVis, "irradiance_cell_vis"}},
                         .indirect = "irradiance_queue",
                         .indirect_offset = 0});
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_relight_pass() { return std::make_unique<IrradianceRelightPass>(); }

}  // namespace gib
