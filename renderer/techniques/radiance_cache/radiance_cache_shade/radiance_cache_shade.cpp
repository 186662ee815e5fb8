#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade.h"

#include <cstddef>

#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

class RadianceCacheShadePass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings&) const override {
    PassDecl d;
    d.name = "radiance_cache_shade";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    // Sparse accesses (bench's memory time counts what they move): each shaded cell reads its
    // rc_active entry and its hit record, and reads and writes its cell.
    d.slots = {{"probe_hits", Access::read, {}, Touched{0, {{"cells_shaded", 1}}, sizeof(glsl::ProbeHit), false}},
               {"rc_active", Access::read, {}, Touched{0, {{"cells_shaded", 1}}, sizeof(uint32_t), true}},
               {"rc_counters", Access::read},
               {"rc_cells", Access::read_write, {}, Touched{0, {{"cells_shaded", 1}}, sizeof(glsl::RcCell), false}},
               {"probe_irradiance", Access::read_prev},
               {"probe_visibility", Access::read_prev}};
    if (scene.features().has(Feature::local_lights)) d.slots.push_back({"light_grid", Access::read});
    // One thread per cell queued this frame: how many, only the GPU knows (read back by bench
    // after its timed frames).
    d.measured = {{"cells_shaded", "rc_counters", offsetof(glsl::RcCounters, active_cells)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    SceneFeatures f = ctx.scene.features();
    const bool local = f.has(Feature::local_lights);
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    const DebugSettings& dbg = ctx.settings.debug;
    RcShadePush push{make_rc_params(ctx.settings, ctx.frame),
                     {r.light_grid_extent, float(r.light_grid_cascades), float(ctx.scene_gpu.light_count), 0.0f},
                     {dbg.injects(2, ctx.frame) ? 1u : 0u, dbg.inject_x, dbg.inject_y, 0}};
    static_assert(sizeof(push) == 112, "RcShadePush must match radiance_cache_shade.comp's push block");
    record_compute(ctx, {.shader = "radiance_cache_shade.comp",
                         // read_prev only: the plain name is last frame's copy.
                         .images = {{kRcShadeBindProbeIrradiance, "probe_irradiance"},
                                    {kRcShadeBindProbeVisibility, "probe_visibility"}},
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kRcShadeSpecSun, f.has(Feature::sun)},
                                            {kRcShadeSpecSky, f.has(Feature::sky)},
                                            {kRcShadeSpecLocal, local},
                                            {kRcShadeSpecAlpha, f.has(Feature::alpha_tested)},
                                            {kRcShadeSpecDither, r.dither_stores ? 1u : 0u}},
                         .buffers = {{kRcShadeBindHits, "probe_hits"},
                                     {kRcShadeBindActive, "rc_active"},
                                     {kRcShadeBindCounters, "rc_counters"},
                                     {kRcShadeBindCells, "rc_cells"},
                                     // Without local lights the shader never reads binding 14,
                                     // but declares it: bind any buffer.
                                     {kRcShadeBindLightGrid, local ? "light_grid" : "rc_counters"}},
                         .indirect = "rc_counters",
                         .indirect_offset = 0});
  }
};

}  // namespace

std::unique_ptr<Pass> make_radiance_cache_shade_pass() { return std::make_unique<RadianceCacheShadePass>(); }

}  // namespace gib
