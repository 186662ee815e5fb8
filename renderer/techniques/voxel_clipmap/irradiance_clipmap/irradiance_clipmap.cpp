#include "renderer/techniques/voxel_clipmap/irradiance_clipmap/irradiance_clipmap.h"

#include "renderer/techniques/voxel_clipmap/irradiance_clipmap/irradiance_clipmap_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class IrradianceClipmapPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "irradiance_clipmap";
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"irradiance_x", Access::read_write, vc_cube_desc(p)},
               {"irradiance_y", Access::read_write, vc_cube_desc(p)},
               {"irradiance_z", Access::read_write, vc_cube_desc(p)},
               {"irradiance_cell_state", Access::read_write, vc_cell_state_desc(p)}};
    d.work = {{"cells", double(vc_cell_count(p))}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    IrrClipmapPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    auto dispatch = [&](uint32_t kernel, const char* label, uint32_t groups) {
      record_compute(ctx, {.shader = "irradiance_clipmap.comp",
                           .groups_x = groups,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kIrrClipmapSpecKernel, kernel}},
                           .buffers = {{kIrrClipmapBindState, "voxel_clip_state"},
                                       {kIrrClipmapBindX, "irradiance_x"},
                                       {kIrrClipmapBindY, "irradiance_y"},
                                       {kIrrClipmapBindZ, "irradiance_z"},
                                       {kIrrClipmapBindCells, "irradiance_cell_state"}},
                           .label = label,
                           .barrier_after = true});
    };
    dispatch(kIrrClipmapOrigins, "irradiance_clipmap/origins", 1);
    dispatch(kIrrClipmapScroll, "irradiance_clipmap/scroll", div_up(uint32_t(vc_cell_count(p)), kIrrClipmapGroup));
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_clipmap_pass() { return std::make_unique<IrradianceClipmapPass>(); }

}  // namespace gib
