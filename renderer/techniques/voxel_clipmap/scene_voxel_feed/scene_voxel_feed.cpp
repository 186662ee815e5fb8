#include "renderer/techniques/voxel_clipmap/scene_voxel_feed/scene_voxel_feed.h"

#include "renderer/techniques/voxel_clipmap/scene_voxel_feed/scene_voxel_feed_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class SceneVoxelFeedPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "scene_voxel_feed";
    d.slots = {{"vbuffer", Access::read},
               {"gbuffer_albedo", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_position", Access::read},
               {"direct_light", Access::read},
               {"gbuffer_emissive", Access::read},
               {"irradiance_x", Access::read},
               {"irradiance_y", Access::read},
               {"irradiance_z", Access::read},
               {"irradiance_cell_state", Access::read},
               {"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"scene_voxel_third", Access::read},
               {"irradiance_cell_vis", Access::read},
               {"voxel_feed_owner", Access::write, vc_buffer(vc_voxel_count(p) * 4, false)}};
    d.work = {{"feed_pixels", double(p.feed_pixels)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    ScFeedPush push{};
    push.vc = make_vc_params(ctx.scene, ctx.settings, ctx.frame);
    uint32_t ids[kScFeedMaxMoving];
    for (uint32_t& id : ids) id = 0xffffffffu;
    uint32_t n = 0;
    for (uint32_t i = 0; i < ctx.scene.instances.size() && n < kScFeedMaxMoving; ++i)
      if (!ctx.scene.instances[i].animation.empty()) ids[n++] = i;
    push.moving[0] = {ids[0], ids[1], ids[2], ids[3]};
    push.moving[1] = {ids[4], ids[5], ids[6], ids[7]};
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("voxel_feed_owner"), 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    for (uint32_t kernel : {kScFeedClaim, kScFeedWrite}) {
      record_compute(ctx, {.shader = "scene_voxel_feed.comp",
                           .images = {{kScFeedBindVbuffer, "vbuffer"},
                                      {kScFeedBindAlbedo, "gbuffer_albedo"},
                                      {kScFeedBindNormal, "gbuffer_normal"},
                                      {kScFeedBindPosition, "gbuffer_position"},
                                      {kScFeedBindDirect, "direct_light"},
                                      {kScFeedBindEmissive, "gbuffer_emissive"}},
                           .groups_x = div_up(p.feed_pixels, kScFeedGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kScFeedSpecKernel, kernel}},
                           .buffers = {{kScFeedBindState, "voxel_clip_state"},
                                       {kScFeedBindVoxels, "scene_voxel_data"},
                                       {kScFeedBindThird, "scene_voxel_third"},
                                       {kScFeedBindVis, "irradiance_cell_vis"},
                                       {kScFeedBindOwner, "voxel_feed_owner"},
                                       {kScFeedBindX, "irradiance_x"},
                                       {kScFeedBindY, "irradiance_y"},
                                       {kScFeedBindZ, "irradiance_z"},
                                       {kScFeedBindCells, "irradiance_cell_state"}},
                           .label = kernel == kScFeedClaim ? "scene_voxel_feed/claim" : "scene_voxel_feed/write",
                           .barrier_after = true});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_scene_voxel_feed_pass() { return std::make_unique<SceneVoxelFeedPass>(); }

}  // namespace gib
