#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update.h"

#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

class IrradianceVolumeUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
    PassDecl d;
    d.name = "irradiance_volume_update";
    ResourceDesc irr{Format::r32_uint, SizeRule::fixed, glsl::kProbeAtlasWidth,
                     glsl::kProbeAtlasRowsPerCascade * r.cascades};
    irr.persistent = true;
    ResourceDesc vis = irr;
    vis.format = Format::rg16_float;
    irr.values = non_negative_values().encoded(Encoding::rgb9e5);  // irradiance / pi
    vis.values = non_negative_values();                             // distance moments
    ResourceDesc rays{Format::buffer, SizeRule::buffer};
    rays.bytes = uint64_t(kProbesPerCascade) * r.rays_per_probe * 16;  // vec4 per ray
    rays.values = non_negative_values().layout(4, 0, 3);                 // rgb radiance
    // Persistent only so that the executor zeroes it once: the GPU kernel never writes it, and
    // the stability scan or a dump then reads zeros, not undefined memory (a fill every frame
    // cost that kernel a 4 MB transfer).
    rays.persistent = true;
    // The per-probe kernel's list of probes left to its fallback dispatch (volume_fallback 0):
    // indirect arguments and probe indices. Ping-pong: each frame appends to its copy and resets
    // last frame's for the next (persistent, so both start zeroed).
    ResourceDesc fallback{Format::buffer, SizeRule::buffer};
    fallback.bytes = (glsl::kIvFallbackListFirst + kProbesPerCascade) * sizeof(uint32_t);
    fallback.persistent = true;
    // The cache is read sparsely (bench's memory time counts what moves): each hit record looks
    // its key up, one slot plus its probing collisions.
    d.slots = {{"probe_hits", Access::read},
               {"rc_cells", Access::read, {},
                Touched{double(rc_hit_records(s)), {{"probing_collisions", 1}}, sizeof(glsl::RcCell), false}},
               {"probe_ray_radiance", Access::write, rays},
               {"probe_irradiance", Access::write, irr},
               {"probe_visibility", Access::write, vis},
               {"probe_irradiance", Access::read_prev},
               {"probe_visibility", Access::read_prev},
               // A few words move: the indirect arguments, the counter, the listed probes.
               {"iv_fallback", Access::write, fallback,
                Touched{double(glsl::kIvFallbackListFirst), {}, sizeof(uint32_t), true}},
               {"iv_fallback", Access::read_prev},  // written: reset for the next frame
               };
    d.work = {{"probes", kProbesPerCascade}};
    return d;
  }

  void record(RecordContext& ctx) override {
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    using namespace glsl;
    // Both ray-shading kernels: cache fallback on; alpha testing (probe rays) when the scene has it.
    const uint32_t dither = r.dither_stores ? 1u : 0u;
    const std::vector<SpecConstant> ray_specs = {{kIvSpecCacheFallback, 1},
                                                 {kIvSpecAlpha, ctx.scene.features().has(Feature::alpha_tested) ? 1u : 0u},
                                                 {kIvSpecDither, dither}};
    // This frame's atlas copy was written two frames ago: it lacks only last frame's update, so
    // that cascade's rows are carried over from last frame's copy. Nothing to carry on the first
    // frame (both copies start zeroed) or when last frame updated this frame's cascade (one
    // cascade); the updated cascade is rewritten whole below. The GPU kernel carries inside its
    // own dispatch (one tile per probe group); the split pair gets a carry dispatch first.
    const uint32_t updated = rc_updated_cascade(r.probe_schedule, r.cascades, ctx.frame);
    const uint32_t last = ctx.frame == 0 ? updated : rc_updated_cascade(r.probe_schedule, r.cascades, ctx.frame - 1);
    const uint32_t carried = last != updated ? last : kIvNoCarry;
    const bool per_probe = r.volume_kernel == 0 ? !ctx.gpu.info().is_software() : r.volume_kernel == 1;
    static_assert(kProbesPerCascade * kProbeTileSize * kProbeTileSize == kProbeAtlasWidth * kProbeAtlasRowsPerCascade,
                  "one probe group per tile of a cascade's rows");
    if (carried != kIvNoCarry && !per_probe) {
      ctx.cmd.begin_label("irradiance_volume_update/carry");
      IvCarryPush carry{carried, 0, 0, 0};
      record_compute(ctx, {.shader = "irradiance_volume_carry.comp",
                           .images = {{kIvBindPrevIrradiance, "probe_irradiance", true},
                                      {kIvBindPrevVisibility, "probe_visibility", true},
                                      {kIvBindIrradiance, "probe_irradiance"},
                                      {kIvBindVisibility, "probe_visibility"}},
                           .groups_x = div_up(kProbeAtlasWidth, 16),
                           .groups_y = div_up(kProbeAtlasRowsPerCascade, 16),
                           .push = &carry,
                           .push_bytes = sizeof(carry),
                           .scene = false});
      ctx.cmd.end_label();
      ctx.cmd.barrier(kStageCompute, kStageCompute);
    }
    IvPush push{make_rc_params(ctx.settings, ctx.frame), {carried, 0, 0, 0}};
    if (per_probe) {
      // GPU: one workgroup per probe with its rays in group-shared memory. With volume_fallback
      // 0, the probes a ray of which finds no shaded cell are listed by the first dispatch and
      // updated by the second (indirect: as many groups as listed), the only one with the
      // fallback's code.
      const bool deferred = r.volume_fallback == 0;
      auto probe_dispatch = [&](const char* label, uint32_t pass, uint32_t cache_fallback, const IvPush& p,
                                bool barrier_after) {
        std::vector<SpecConstant> specs = ray_specs;
        specs[0] = {kIvSpecCacheFallback, cache_fallback};
        specs.push_back({kIvSpecRays, r.rays_per_probe});  // 1..kIvMaxRays (probe_trace checks)
        specs.push_back({kIvSpecPass, pass});
        ctx.cmd.begin_label(std::string("irradiance_volume_update/") + label);
        record_compute(ctx, {.shader = "irradiance_volume_probe.comp",
                             .images = {{kIvBindPrevIrradiance, "probe_irradiance", true},
                                        {kIvBindPrevVisibility, "probe_visibility", true},
                                        {kIvBindIrradiance, "probe_irradiance"},
                                        {kIvBindVisibility, "probe_visibility"}},
                             .groups_x = kProbesPerCascade,
                             .push = &p,
                             .push_bytes = sizeof(p),
                             .spec_constants = specs,
                             .buffers = {{kIvBindHits, "probe_hits"},
                                         {kIvBindCells, "rc_cells"},
                                         {kIvBindFallback, "iv_fallback"},
                                         {kIvBindNextFallback, "iv_fallback", true}},
                             .indirect = pass == kIvPassFallback ? "iv_fallback" : nullptr,
                             .barrier_after = barrier_after});
        ctx.cmd.end_label();
      };
      if (!deferred) {
        probe_dispatch("probe", kIvPassAll, 1, push, false);
        return;  // probe_ray_radiance, the split path's, stays as created: zero
      }
      probe_dispatch("probe", kIvPassCached, 0, push, true);
      IvPush fallback_push = push;
      fallback_push.extra.x = kIvNoCarry;  // the first dispatch carried
      probe_dispatch("fallback", kIvPassFallback, 1, fallback_push, false);
      return;
    }
    // CPU device: two barrier-free kernels (see irradiance_volume_probe.comp for why).
    ctx.cmd.begin_label("irradiance_volume_update/rays");
    record_compute(ctx, {.shader = "irradiance_volume_rays.comp",
                         .images = {{kIvBindPrevIrradiance, "probe_irradiance", true},
                                    {kIvBindPrevVisibility, "probe_visibility", true}},
                         .groups_x = div_up(kProbesPerCascade * r.rays_per_probe, kIvRaysGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = ray_specs,
                         .buffers = {{kIvBindHits, "probe_hits"}, {kIvBindCells, "rc_cells"},
                                     {kIvBindRays, "probe_ray_radiance"}}});
    ctx.cmd.end_label();
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    ctx.cmd.begin_label("irradiance_volume_update/convolve");
    record_compute(ctx, {.shader = "irradiance_volume_update.comp",
                         .images = {{kIvBindPrevIrradiance, "probe_irradiance", true},
                                    {kIvBindPrevVisibility, "probe_visibility", true},
                                    {kIvBindIrradiance, "probe_irradiance"},
                                    {kIvBindVisibility, "probe_visibility"}},
                         .groups_x = div_up(kProbesPerCascade * kProbeTileSize * kProbeTileSize, kIvConvolveGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kIvSpecDither, dither}},
                         .buffers = {{kIvBindRays, "probe_ray_radiance"}}});
    ctx.cmd.end_label();
  }
};

}  // namespace

std::unique_ptr<Pass> make_irradiance_volume_update_pass() { return std::make_unique<IrradianceVolumeUpdatePass>(); }

}  // namespace gib
