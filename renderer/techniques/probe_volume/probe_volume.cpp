// `probe-volume`: Assassin's Creed Shadows' ray-traced diffuse GI (SIGGRAPH 2025 "Ray tracing
// in Assassin's Creed Shadows": probe volume, per-pixel diffuse, translucency, alpha
// strategies, light-leak mitigations). Design notes: probe_volume.md beside this file.
#include "renderer/techniques/probe_volume/probe_volume.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"

#include "renderer/passes/composite/composite.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/probe_volume/hit_lighting/hit_lighting.h"
#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise.h"
#include "renderer/techniques/probe_volume/pixel_upscale/pixel_upscale.h"
#include "renderer/techniques/probe_volume/probe_classify/probe_classify.h"
#include "renderer/techniques/probe_volume/probe_convolve/probe_convolve.h"
#include "renderer/techniques/probe_volume/probe_gbuffer/probe_gbuffer.h"
#include "renderer/techniques/probe_volume/probe_relight/probe_relight.h"
#include "renderer/techniques/probe_volume/probe_relocate/probe_relocate.h"
#include "renderer/techniques/probe_volume/probe_select/probe_select.h"
#include "renderer/techniques/probe_volume/probe_volume_stages.h"
#include "renderer/techniques/probe_volume/screen_trace/screen_trace.h"
#include "renderer/techniques/probe_volume/world_trace/world_trace.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {
// The seed's budgets: 1024 probes per frame (512 on Series S and in 60 fps modes); rays at
// quarter resolution (full at 'ultra'); direct_lighting's sky-ray ladder of the other techniques.
struct Preset {
  const char* name;
  uint32_t probe_budget, pixel_divisor, sky_rays;
};
constexpr Preset kPresets[] = {{"low", 512, 2, 1}, {"medium", 1024, 2, 4}, {"high", 1024, 2, 16}, {"ultra", 1024, 1, 64}};
void apply_preset_row(ProbeVolumeSettings& s, const Preset& p) {
  s.probe_budget = p.probe_budget;
  s.pixel_divisor = p.pixel_divisor;
  s.sky_rays = p.sky_rays;
}

using S = ProbeVolumeSettings;
std::vector<TechniqueOption> own_options() {
  return {
      option("sky_rays", "direct_lighting's cosine rays per pixel for sky and emissive light (0: none)", 0, 4096,
             &DirectLightingParams::sky_rays),
      option("cascades", "probe cascades (spacing doubles per cascade)", 1, 8, &S::cascades),
      option("grid_xz", "probes per cascade along x and z", 2, 64, &S::grid_xz),
      option("grid_y", "probes per cascade along y (up)", 2, 64, &S::grid_y),
      option("probe_spacing", "metres between cascade-0 probes", 0.01, 1000, &S::probe_spacing),
      option("forward_offset", "the volume's centre sits this share of its width ahead of the camera", 0, 0.5,
             &S::forward_offset),
      option("probe_budget", "probes updated per frame (new, then G-buffer refreshes, then relight only)", 1, 65536,
             &S::probe_budget),
      option("gbuffer_share", "share of the budget left after new probes that re-traces G-buffers", 0, 1,
             &S::gbuffer_share),
      option("quarter_res_new", "new probes trace one ray per 2x2 texels (0/1)", 0, 1, &S::quarter_res_new),
      option("trace_range", "probe rays reach this many cascade spacings", 0.1, 1000, &S::trace_range),
      option("multi_bounce", "probe hits add last frame's probe irradiance (0: single bounce, a control)", 0, 1,
             &S::multi_bounce),
      option("lighting_scale",
             "probes not relit follow the sun/sky change through their lighting scale (0: they lag, the control)", 0,
             1, &S::lighting_scale),
      option("visibility_test", "leak mitigation: Chebyshev test on the probes' depth moments (0/1)", 0, 1,
             &S::visibility_test),
      option("normal_offset", "leak mitigation: cascade spacings along the normal before sampling probes", 0, 2,
             &S::normal_offset),
      option("view_offset", "leak mitigation: cascade spacings towards the viewer before sampling probes", 0, 2,
             &S::view_offset),
      option("inverse_ray_offset",
             "leak mitigation: sampling point moved back along the incoming ray, at most half its length (0/1)", 0, 1,
             &S::inverse_ray_offset),
      option("probe_ao", "leak mitigation: irradiance at hits closer than a probe spacing darkened (0/1)", 0, 1,
             &S::probe_ao),
      option("relocation", "leak mitigation: probes moved out of / away from geometry, disabled when stuck (0/1)", 0,
             1, &S::relocation),
      option("indoor_classes",
             "leak mitigation: points blend only probes of their class, indoor (inside the scene's indoor volumes) or "
             "outdoor (0/1)",
             0, 1, &S::indoor_classes),
      option("nearest_weight", "nearest-probe fast path above this trilinear weight (> 1: always 8 probes)", 0, 2,
             &S::nearest_weight),
      option("lookup_view",
             "diagnostic: each ray pixel carries the probes' irradiance at its own surface instead of its ray's "
             "light (the probe lookups against the reference's one-interreflection image; 0/1)",
             0, 1, &S::lookup_view),
      option("pixel_divisor", "per-pixel rays at 1/2 (quarter resolution) or 1 (full)", 1, 2, &S::pixel_divisor),
      option("screen_steps", "screen_trace steps per ray (0: every ray traced in the BVH)", 0, 256, &S::screen_steps),
      option("screen_thickness", "metres behind the depth buffer a screen_trace hit may lie", 0, 100,
             &S::screen_thickness),
      option("min_start",
             "metres per-pixel rays skip at their start (the seed's 0.05: it tunnels through the wall next to a "
             "corner; ours start from an offset origin)",
             0, 1, &S::min_start),
      option("screen_resume",
             "world_trace resumes screen_trace's rays from their last point in front of the depth buffer (the seed's "
             "backtracking; 1 leaks where a pixel straddles a silhouette: extreme-range) instead of from the start",
             0, 1, &S::screen_resume),
      option("pixel_range", "per-pixel rays reach this many times the probe trace range", 0.1, 100, &S::pixel_range),
      option("denoise_radius", "pixel_denoise spatial half-width in ray pixels (0: off)", 0, 8, &S::denoise_radius),
      option("history_max_frames", "pixel_denoise temporal n_max (1: no history)", 1, 1024, &S::history_max_frames),
      option("anti_lag_sigma",
             "pixel_denoise anti-lag: the history is clamped to the fast history +- this many standard deviations of "
             "their difference, estimated from the frame's noise (0: off)",
             0, 100, &S::anti_lag_sigma),
      option("fast_history_frames", "pixel_denoise anti-lag: the fast history's n_max", 1, 64,
             &S::fast_history_frames),
      option("material_mask", "pixel_denoise keeps translucent and opaque pixels apart (0/1)", 0, 1,
             &S::material_mask),
      option("translucent_rays",
             "per-pixel rays on translucent surfaces take the back side with probability t/(1+t) (0: front only)", 0,
             1, &S::translucent_rays),
  };
}
// The probes after the last frame, per cascade: how many are valid, disabled, indoor, moved,
// and the spread of their mean luminance and sky visibility by class (the seed's probe debug
// views, as text).
std::string print_probes(const std::vector<uint8_t>& bytes, uint32_t, uint32_t) {
  using namespace glsl;
  const size_t header = kPvMaxCascades * sizeof(PvCascade);
  if (bytes.size() < header) return "probe_state: empty\n";
  const size_t count = (bytes.size() - header) / sizeof(PvProbe);
  std::vector<PvProbe> probes(count);
  std::memcpy(probes.data(), bytes.data() + header, count * sizeof(PvProbe));
  std::string out = "cascade  probes  valid  disabled  indoor  moved | indoor: mean lum max / mean, sky vis max | outdoor: same\n";
  uint32_t cascades = 0;  // probe_select marks the run's cascades (rr.w)
  for (uint32_t c = 0; c < kPvMaxCascades; ++c) {
    PvCascade pc;
    std::memcpy(&pc, bytes.data() + c * sizeof(PvCascade), sizeof(pc));
    if (pc.rr.w) cascades = c + 1;
  }
  if (cascades == 0) return "probe_state: no cascade selected yet\n";
  const size_t per = count / cascades;
  for (uint32_t c = 0; c < cascades; ++c) {
    uint32_t valid = 0, disabled = 0, indoor = 0, moved = 0;
    double lum_max[2] = {0, 0}, lum_sum[2] = {0, 0}, sky_max[2] = {0, 0};
    uint32_t n[2] = {0, 0};
    for (size_t i = c * per; i < (c + 1) * per; ++i) {
      const PvProbe& p = probes[i];
      const uint32_t f = uint32_t(p.coord.w);
      const int k = (f & kPvProbeIndoor) ? 0 : 1;
      valid += (f & kPvProbeValid) != 0;
      disabled += (f & kPvProbeDisabled) != 0;
      indoor += k == 0;
      moved += p.offset.x != 0 || p.offset.y != 0 || p.offset.z != 0;
      if (!(f & kPvProbeValid) || (f & kPvProbeDisabled)) continue;
      lum_max[k] = std::max(lum_max[k], double(p.meta.w));
      lum_sum[k] += p.meta.w;
      sky_max[k] = std::max(sky_max[k], double(p.meta.x));
      ++n[k];
    }
    out += fmt::format("{:>7} {:>7} {:>6} {:>9} {:>7} {:>6} | {:.4g} / {:.4g}, {:.3f} | {:.4g} / {:.4g}, {:.3f}\n", c, per, valid,
                       disabled, indoor, moved, lum_max[0], n[0] ? lum_sum[0] / n[0] : 0.0, sky_max[0], lum_max[1],
                       n[1] ? lum_sum[1] / n[1] : 0.0, sky_max[1]);
  }
  return out;
}

}  // namespace

Technique probe_volume_technique() {
  Technique t;
  t.name = "probe-volume";
  t.description =
      "AC Shadows RTGI: camera-following probe cascades with a per-frame budget, cached probe G-buffer relit every "
      "update, irradiance / radiance / depth-moment probes; per-pixel cosine rays lit from them, YCoCg SH, denoise, "
      "upscale (renderer/techniques/probe_volume/probe_volume.md)";
  t.passes = {{"visibility", make_visibility_pass},
              {"gbuffer", make_gbuffer_pass},
              {"direct_lighting", make_direct_lighting_pass},
              {"probe_select", make_probe_select_pass},
              {"probe_classify", make_probe_classify_pass},
              {"probe_gbuffer", make_probe_gbuffer_pass},
              {"probe_relight", make_probe_relight_pass},
              {"probe_convolve", make_probe_convolve_pass},
              {"probe_relocate", make_probe_relocate_pass},
              {"screen_trace", make_screen_trace_pass},
              {"world_trace", make_world_trace_pass},
              {"hit_lighting", make_hit_lighting_pass},
              {"pixel_denoise", make_pixel_denoise_pass},
              {"pixel_upscale", make_pixel_upscale_pass},
              {"composite", make_composite_pass}};
  t.output = "final_color";
  t.contract_aovs = {{"direct", "direct_radiance"}, {"indirect_diffuse", "indirect_diffuse"}};
  t.aovs = {"indirect_diffuse", "direct_radiance", "gi_irradiance",  "direct_light",   "pixel_gi_y",
            "gbuffer_albedo",   "gbuffer_normal",  "gbuffer_position"};
  t.stats = {
      {"new_probes", "probes entering the volume updated this frame (full update, quarter resolution)",
       "probe_selection", 8},
      {"gbuffer_probes", "probes whose G-buffer was re-traced this frame (round robin)", "probe_selection", 9},
      {"relight_probes", "probes relit from their cached G-buffer this frame (round robin)", "probe_selection", 10},
      {"waiting_probes", "new probes over the budget, left for later frames", "probe_selection", 11},
      {"hit_texels", "probe texels lit as hits this frame", "probe_texel_lists", 3},
      {"miss_texels", "probe texels lit as misses this frame", "probe_texel_lists", 7},
      {"screen_hit_share", "per-pixel rays that hit on screen (screen_trace), of the valid ray pixels",
       "pixel_trace_stats", 1, 0},
      {"screen_miss_share", "per-pixel rays whose whole range stayed in front of the depth buffer", "pixel_trace_stats",
       2, 0},
      {"world_share", "per-pixel rays traced in the BVH (world_trace)", "pixel_trace_stats", 3, 0},
  };
  t.printouts = {{"probes", "the probes after the last frame per cascade: valid, disabled, indoor, moved; mean luminance and sky visibility by class",
                  "probe_state", print_probes}};
  t.stages = probe_volume_stages();
  define_settings<ProbeVolumeSettings>(t, kPresets, apply_preset_row);
  t.options = with_common_options(own_options(), {0, 1});
  add_direct_light_modes(t);  // option direct_light: traced or shadow_mapped
  return t;
}

}  // namespace gib
