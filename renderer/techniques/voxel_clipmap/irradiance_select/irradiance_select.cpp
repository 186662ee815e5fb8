#include "renderer/techniques/voxel_clipmap/irradiance_select/irradiance_select.h"

#include "renderer/techniques/voxel_clipmap/irradiance_select/irradiance_select_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class IrradianceSelectPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    // The list (queue_a + queue_b entries), then scratch lists A', A, B and A out of view.
    const uint64_t entries = 2ull * vc_queue_capacity(p) + p.queue_a_new + p.queue_a;
    PassDecl d;
    d.name = "irradiance_select";
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"irradiance_cell_state", Access::read_write, vc_cell_state_desc(p)},
               {"irradiance_queue", Access::write, vc_buffer(sizeof(glsl::VcQueue) + entries * 4, false)}};
    d.work = {{"cells", double(vc_cell_count(p))}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    IrrSelectPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    record_compute(ctx, {.shader = "irradiance_select.comp",
                         .groups_x = 1,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = {{kIrrSelectBindState, "voxel_clip_state"},
                                     {kIrrSelectBindVoxels, "scene_voxel_data"},
                                     {kIrrSelectBindCells, "irradiance_cell_state"},
                                     {kIrrSelectBindQueue, "irradiance_queue"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_select_pass() { return std::make_unique<IrradianceSelectPass>(); }

}  // namespace gib
