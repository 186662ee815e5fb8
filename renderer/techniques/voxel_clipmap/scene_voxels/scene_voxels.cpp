#include "renderer/techniques/voxel_clipmap/scene_voxels/scene_voxels.h"

#include "renderer/techniques/voxel_clipmap/scene_voxels/scene_voxels_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class SceneVoxelsPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    check_vc_settings(p);
    PassDecl d;
    d.name = "scene_voxels";
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)}};
    d.work = {{"voxels", double(vc_voxel_count(p))}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    ScVoxelsPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    auto dispatch = [&](uint32_t kernel, const char* label, uint32_t groups) {
      record_compute(ctx, {.shader = "scene_voxels.comp",
                           .groups_x = groups,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kScVoxelsSpecKernel, kernel}},
                           .buffers = {{kScVoxelsBindState, "voxel_clip_state"}, {kScVoxelsBindVoxels, "scene_voxel_data"}},
                           .label = label,
                           .barrier_after = true});
    };
    dispatch(kScVoxelsOrigins, "scene_voxels/origins", 1);
    dispatch(kScVoxelsScroll, "scene_voxels/scroll", div_up(uint32_t(vc_voxel_count(p)), kScVoxelsGroup));
  }
};

}  // namespace

std::unique_ptr<Pass> make_scene_voxels_pass() { return std::make_unique<SceneVoxelsPass>(); }

}  // namespace gib
