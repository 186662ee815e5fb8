// `radiance-cache`: idTech 8's GI (idTech 8 "Global Illumination" talk: light grid, world
// sampling, radiance cache, irradiance volumes, final gather, denoise, upscale). Design notes:
// radiance_cache.md beside this file.
#include "renderer/techniques/radiance_cache/radiance_cache.h"

#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/radiance_cache/exposure/exposure.h"
#include "renderer/techniques/radiance_cache/final_gather/final_gather.h"
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite.h"
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise.h"
#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve.h"
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.h"
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update.h"
#include "renderer/techniques/radiance_cache/light_grid/light_grid.h"
#include "renderer/techniques/radiance_cache/probe_trace/probe_trace.h"
#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade.h"
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"
#include "renderer/techniques/radiance_cache/radiance_cache_stages.h"

namespace gib {
namespace {
// The seed's platform tiers: 16/32/64 rays per probe, 1/4 or 1/2 gather, more cascades with
// quality (6 ship). ultra goes past the seed: it gathers at full resolution (4x high's gather
// rays), the one step up that lowers the error of a small interior, where cascades beyond the
// fourth reach nothing (with 6 cascades and a 1/2 gather ultra errs as much as high).
//
// Cache size: every preset has the seed's 14 MB (2^20 cells of 16 B). Cells are never evicted, so
// a small table fills, its insertions are dropped, and their gather rays and bounces fall back to
// the volumes, which hold no direct light: with 2^13 cells the thin-wall room reads 0.83-0.85 of
// the reference at low (H100, CI tier) and 0.81 at the GPU tier (1.00 with 2^20 cells), and with
// 2^15 cells medium reads 0.974 at the GPU tier (1.011 with 2^20); radiance_cache.md,
// "Cache size".
//
// high and ultra: with one cascade updated per frame in turn and the same hysteresis, more
// cascades update each probe less often, so the bounce light that builds up from frame to frame
// (the volumes feed the next frame's cells) converges slower at the higher presets: a closed
// 0.99 box reads 0.495 / 0.474 / 0.275 / 0.208 of its analytic value after 400 frames at low /
// medium / high / ultra that way (lavapipe, 64x36). So at high and ultra the finest cascade is
// updated every other frame (schedule 1, below), and their hysteresis keeps medium's noise
// instead of its speed: a probe's blended irradiance averages about rays x (1 + h) / (1 - h) ray
// samples (an exponential moving average with weight 1 - h), 32 x 1.85 / 0.15 = 395 at medium;
// 64 rays reach that at h = 0.721. Every preset stores the probe atlas, the GI history and the
// cache cells with stochastic rounding (dither_stores): rounded to nearest, a slowly converging
// blend stops short of its limit (radiance_cache.md, "Quantised stores"). low and medium keep
// schedule 0 and their hysteresis: on an H100 after 3000 frames the closed box reads low 0.907 /
// medium 0.888 rounded to nearest, 0.994 / 0.990 with every store dithered.
struct Preset {
  const char* name;
  uint32_t rays_per_probe, gather_divisor, cascades, cache_log2_cells, probe_schedule;
  bool dither_stores;
};
constexpr Preset kPresets[] = {{"low", 16, 4, 2, 20, 0, true},
                               {"medium", 32, 2, 3, 20, 0, true},
                               {"high", 64, 2, 4, 20, 1, true},
                               {"ultra", 64, 1, 6, 20, 1, true}};
// Ray samples a probe texel averages at medium (32 rays, hysteresis 0.85).
constexpr float kMediumProbeSamples = 32.0f * (1.0f + 0.85f) / (1.0f - 0.85f);
void apply_preset_row(RadianceCacheSettings& s, const Preset& p) {
  s.rays_per_probe = p.rays_per_probe;
  s.gather_divisor = p.gather_divisor;
  s.cascades = p.cascades;
  s.cache_log2_cells = p.cache_log2_cells;
  s.probe_schedule = p.probe_schedule;
  s.dither_stores = p.dither_stores;
  if (p.rays_per_probe > 32) {
    const float k = kMediumProbeSamples / float(p.rays_per_probe);  // (1 + h) / (1 - h)
    s.probe_hysteresis = (k - 1.0f) / (k + 1.0f);
  }
}

using S = RadianceCacheSettings;
std::vector<TechniqueOption> own_options() {
  return {
      option("visibility_test", "leak mitigation: Chebyshev test on probe distance moments (0/1)", 0, 1,
             &S::visibility_test),
      option("normal_bias", "leak mitigation: metres along the normal before sampling probes", 0, 10, &S::normal_bias),
      option("view_bias", "leak mitigation: metres towards the viewer before sampling probes", 0, 10, &S::view_bias),
      option("probe_rays",
             "leak mitigation: a shadow ray from each point that samples the volumes to each of its 8 probes; "
             "blocked probes get no weight (0/1)",
             0, 1, &S::probe_rays),
      option("cache_side_key", "leak mitigation: radiance-cache cells keyed by surface side (0/1)", 0, 1,
             &S::cache_side_key),
      option("inside_test",
             "leak mitigation: probes whose rays meet the back of a solid or a surface nearer than 1e-3 spacings "
             "are inside geometry: not sampled, no cache cells; bounce rays meeting a solid's back bring 0 (0/1)",
             0, 1, &S::inside_test),
      option("disocclusion", "temporal filter rejects history failing depth/normal tests (0/1)", 0, 1,
             &S::disocclusion),
      option("history_format", "GI history: 0 RGB9E5, 1 RGBA16F, 2 R11G11B10F, 3 RGBA32F", 0, 3, &S::history_format),
      option("history_max_frames", "n_max of the temporal filter", 1, 1024, &S::history_max_frames),
      option("cascades", "irradiance-volume cascades", 1, 8, &S::cascades),
      option("dither_stores",
             "the RGB9E5 probe atlas and GI history round stochastically, so their blends do not stick "
             "short of a slowly converging value (0/1)",
             0, 1, &S::dither_stores),
      option("probe_schedule",
             "which cascade's probes a frame updates: 0 each in turn, 1 the finest every other frame and the "
             "others in turn between",
             0, 1, &S::probe_schedule),
      option("rays_per_probe", "visibility rays per updated probe", 1, 64, &S::rays_per_probe),
      option("probe_spacing", "metres between cascade-0 probes", 0.01, 100, &S::probe_spacing),
      option("gather_divisor", "final gather at full, 1/2 or 1/4 resolution (1, 2 or 4; 3 reads as 2)", 1, 4, &S::gather_divisor),
      option("cache_log2_cells", "radiance cache capacity, log2 cells", 4, 24, &S::cache_log2_cells),
      option("cache_reuse_frames", "frames a shaded cache cell is reused", 1, 1024, &S::cache_reuse_frames),
      option("cache_cell_size", "metres across a radiance-cache cell at LOD 0", 0.01, 10, &S::cache_cell_size),
      option("cache_lod_distance",
             "metres from the camera per cell LOD step: a cell at distance d is cache_cell_size x 2^floor(log2(1 + d / "
             "this)) across",
             0.1, 1e6, &S::cache_lod_distance),
      option("denoise_hit_weight",
             "gi_denoise weighs the bounce SH's taps by hit-distance similarity too, as the seed (0/1; default 0: the "
             "weight depends on the values and biases the mean; the direct part always takes geometry weights only)",
             0, 1, &S::denoise_hit_weight),
      option("denoise_radius", "bilateral half-width in gather pixels (0: off)", 0, 16, &S::denoise_radius),
      option("probe_hysteresis", "weight of last frame's probe texel when blending (0: no history)", 0, 0.999,
             &S::probe_hysteresis),
      option("multi_bounce",
             "1: caches feed back on themselves (cells and volumes shade bounces from last frame's volumes, the "
             "gather reads last frame's image); 0: single bounce (white-furnace negative control)",
             0, 1, &S::multi_bounce),
      option("pre_exposure",
             "1: the gather, denoise and upscale work on radiance x P, P = 1 / log-average luminance of the frame "
             "(exposure pass), so RGBA16F SH and the history do not clamp under bright light; 0: P = 1 (negative "
             "control)",
             0, 1, &S::pre_exposure),
      option("volume_kernel",
             "irradiance_volume_update's kernels: 0 by device (GPU: one workgroup per probe; CPU device: the split "
             "ray/convolve pair), 1 per-probe, 2 split; the same math, so a cross-device difference can be isolated",
             0, 2, &S::volume_kernel),
      option("volume_fallback",
             "the per-probe volume kernel's cache fallback (a hit whose cell is not shaded): 0 in a second, indirect "
             "dispatch over the probes that have such a ray (none in a steady frame), which the first dispatch "
             "lists instead of updating them, so the first carries none of its code; 1 inline in the one dispatch; "
             "the same atlas",
             0, 1, &S::volume_fallback),
      option("insertion_rounds",
             "radiance_cache_update's insertion rounds 1 .. cache_max_probe: 0 in one dispatch of one workgroup "
             "(a barrier between rounds), 1 one indirect dispatch per round; the same table and counters",
             0, 1, &S::insertion_rounds),
      option("insertion_find",
             "radiance-cache insertion round 0 (the find: each hit's key searched, placed, queued or bid): 0 in "
             "probe_trace as each ray is traced (the seed's: the trace triggers the cache update), 1 in a dispatch "
             "of its own at the start of radiance_cache_update over every hit record; the same table and counters",
             0, 1, &S::insertion_find),
      option("update_counters",
             "radiance_cache_update's counters: 0 by device (GPU: summed per workgroup in shared memory, one atomic "
             "per workgroup; CPU device: one atomic per subgroup, no group barrier), 1 per workgroup, 2 per subgroup; "
             "the same sums",
             0, 2, &S::update_counters),
      option("denoise_kernel",
             "gi_denoise's kernel: 0 both directions in one dispatch, each group filtering a shared-memory tile "
             "of its pixels and radius more on every side (the seed's group-shared memory) where the radius fits "
             "it (<= 4), else as 2; 1 two dispatches, each tap reads the images; 2 two dispatches, each group "
             "preloads its taps along the axis into shared memory where the radius fits (<= 8), else as 1; the "
             "same values and arithmetic",
             0, 2, &S::denoise_kernel),
      option("upscale_kernel",
             "gi_upscale's kernel: 0 each group preloads the gather samples its taps reach into shared memory, 1 "
             "each tap reads the images; the same values and arithmetic",
             0, 1, &S::upscale_kernel),
  };
}
}  // namespace

Technique radiance_cache_technique() {
  Technique t;
  t.name = "radiance-cache";
  t.description =
      "idTech 8 GI: light grid, cascaded irradiance volumes, world radiance cache, 1/2-1/4 res final gather, "
      "bilateral denoise, upscale + temporal filter (renderer/techniques/radiance_cache/radiance_cache.md)";
  t.passes = {{"visibility", make_visibility_pass},
              {"gbuffer", make_gbuffer_pass},
              {"direct_lighting", make_direct_lighting_pass},
              {"light_grid", [] { return make_light_grid_pass(); }},
              {"probe_trace", make_probe_trace_pass},
              {"radiance_cache_update", make_radiance_cache_update_pass},
              {"radiance_cache_shade", make_radiance_cache_shade_pass},
              {"irradiance_volume_update", make_irradiance_volume_update_pass},
              {"exposure", make_exposure_pass},
              {"final_gather", make_final_gather_pass},
              {"gi_denoise", make_gi_denoise_pass},
              {"gi_upscale", make_gi_upscale_pass},
              {"gi_composite", make_gi_composite_pass},
              {"gi_resolve", make_gi_resolve_pass}};
  t.output = "final_color";
  t.contract_aovs = {{"direct", "direct_radiance"}, {"indirect_diffuse", "indirect_diffuse"}};
  t.aovs = {"indirect_diffuse", "direct_radiance",  "gi_irradiance",  "gi_direct_irradiance", "direct_light",
            "probe_irradiance", "probe_visibility", "gather_sh_r",    "gather_direct",        "gbuffer_albedo",
            "gbuffer_normal",   "gbuffer_position"};
  t.stages = radiance_cache_stages();
  define_settings<RadianceCacheSettings>(t, kPresets, apply_preset_row);
  t.options = with_common_options(own_options(), {0, 1, 2});
  add_direct_light_modes(t);  // option direct_light: traced or shadow_mapped
  return t;
}

}  // namespace gib
