#include "renderer/techniques/voxel_clipmap/scene_voxel_light/scene_voxel_light.h"

#include "renderer/techniques/voxel_clipmap/scene_voxel_light/scene_voxel_light_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

class SceneVoxelLightPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "scene_voxel_light";
    d.slots = {{"irradiance_x", Access::read},
               {"irradiance_y", Access::read},
               {"irradiance_z", Access::read},
               {"irradiance_cell_state", Access::read},
               {"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"scene_voxel_third", Access::read},
               {"irradiance_cell_vis", Access::read}};
    d.work = {{"voxels", double(vc_lit_visits(p))}};
    d.traces_rays = true;
    if (!p.geometry_light) d.switched_off = "geometry_light is 0";
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    const uint32_t visits = vc_lit_visits(p);
    ScLightPush push{make_vc_params(ctx.scene, ctx.settings, ctx.frame)};
    const SceneFeatures f = ctx.scene.features();
    record_compute(ctx, {.shader = "scene_voxel_light.comp",
                         .groups_x = div_up(visits, kScLightGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kScLightSpecAlpha, f.has(Feature::alpha_tested)},
                                            {kScLightSpecSun, f.has(Feature::sun)},
                                            {kScLightSpecLocal, f.has(Feature::local_lights)}},
                         .buffers = {{kScLightBindState, "voxel_clip_state"},
                                     {kScLightBindVoxels, "scene_voxel_data"},
                                     {kScLightBindThird, "scene_voxel_third"},
                                     {kScLightBindVis, "irradiance_cell_vis"},
                                     {kScLightBindX, "irradiance_x"},
                                     {kScLightBindY, "irradiance_y"},
                                     {kScLightBindZ, "irradiance_z"},
                                     {kScLightBindCells, "irradiance_cell_state"}},
                         .barrier_after = true});
  }
};

}  // namespace

std::unique_ptr<Pass> make_scene_voxel_light_pass() { return std::make_unique<SceneVoxelLightPass>(); }

}  // namespace gib
