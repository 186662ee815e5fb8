#include "renderer/techniques/voxel_clipmap/scene_voxel_fill/scene_voxel_fill.h"

#include "renderer/techniques/voxel_clipmap/scene_voxel_fill/scene_voxel_fill_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class SceneVoxelFillPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "scene_voxel_fill";
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"scene_voxel_third", Access::read_write, vc_third_desc(p)},
               {"voxel_geometry", Access::write, vc_buffer(vc_voxel_count(p) * 12, false)}};
    d.work = {{"voxels", double(vc_voxel_count(p))}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    ScFillPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("voxel_geometry"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const std::vector<BufferBinding> buffers{{kScFillBindState, "voxel_clip_state"},
                                             {kScFillBindVoxels, "scene_voxel_data"},
                                             {kScFillBindThird, "scene_voxel_third"},
                                             {kScFillBindGeometry, "voxel_geometry"}};
    auto dispatch = [&](uint32_t kernel, const char* label, uint32_t items) {
      record_compute(ctx, {.shader = "scene_voxel_fill.comp",
                           .groups_x = div_up(items, kScFillGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kScFillSpecKernel, kernel}},
                           .buffers = buffers,
                           .label = label,
                           .barrier_after = true});
    };
    if (p.geometry_fill && ctx.scene_gpu.triangle_count > 0)
      dispatch(kScFillVoxelize, "scene_voxel_fill/voxelize", ctx.scene_gpu.triangle_count * p.levels);
    dispatch(kScFillMerge, "scene_voxel_fill/merge", uint32_t(vc_voxel_count(p)));
  }
};

}  // namespace

std::unique_ptr<Pass> make_scene_voxel_fill_pass() { return std::make_unique<SceneVoxelFillPass>(); }

}  // namespace gib
