// `gow-ragnarok`: God of War Ragnarök's sun shadows (gow_ragnarok.md) on the visibility-buffer
// and G-buffer path of `direct`: cascaded shadow maps, a dilated min/max depth map, and the sun's
// visibility by Poisson-style PCF (the baseline) or contact-hardening shadows marched through the
// shadow map; direct_lighting takes the sun's visibility from the selected pass instead of
// tracing a shadow ray. Local lights have no shadow maps: ssdo lights them through screen-space
// directional occlusion; ssgi adds a screen-space bounce. In scenes with a glossy material,
// ray-traced cube-map reflections (cubemap_capture, reflections_rt_cubemap, reflections_resolve)
// give the AOV `reflection`.
#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"

#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/gow_ragnarok/cubemap_capture/cubemap_capture.h"
#include "renderer/techniques/gow_ragnarok/direct_aov/direct_aov.h"
#include "renderer/techniques/gow_ragnarok/reflections_resolve/reflections_resolve.h"
#include "renderer/techniques/gow_ragnarok/reflections_rt_cubemap/reflections_rt_cubemap.h"
#include "renderer/techniques/gow_ragnarok/reflections_rt_cubemap/reflections_rt_cubemap_shared.h"
#include "renderer/passes/shadow_maps/shadow_maps.h"
#include "renderer/passes/shadow_minmax/shadow_minmax.h"
#include "renderer/techniques/gow_ragnarok/shadows_contact_hardening/shadows_contact_hardening.h"
#include "renderer/passes/shadows_pcf/shadows_pcf.h"
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space_shared.h"
#include "renderer/techniques/gow_ragnarok/ssdo/ssdo.h"
#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi.h"
#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi_shared.h"
#include "renderer/techniques/gow_ragnarok/ssgi/ssgi.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"
#include "renderer/techniques/gow_ragnarok/gow_ragnarok_stages.h"

namespace gib {
namespace {

struct Preset {
  const char* name;
  uint32_t cascades, resolution, taps, march_steps, sky_rays;
  uint32_t ssdo_directions, ssdo_steps, ssgi_directions, ssgi_steps;  // ssdo/, ssgi/
};
constexpr Preset kPresets[] = {{"low", 2, 512, 8, 6, 1, 4, 4, 4, 8},
                               {"medium", 3, 1024, 16, 10, 4, 8, 6, 8, 12},
                               {"high", 4, 2048, 24, 14, 16, 12, 8, 16, 16},
                               {"ultra", 4, 4096, 32, 20, 64, 16, 12, 32, 24}};

// The slot direct_lighting reads the sun's visibility from: the selected filter's output.
std::string_view visibility_slot(uint32_t filter) {
  return filter == uint32_t(ShadowFilter::pcf) ? "shadow_pcf" : "shadow_contact_hardening";
}

void apply_row(GowRagnarokSettings& s, const Preset& p) {
  s.shadow_cascades = p.cascades;
  s.shadow_resolution = p.resolution;
  s.shadow_taps = p.taps;
  s.shadow_march_steps = p.march_steps;
  s.sky_rays = p.sky_rays;
  s.ssdo_directions = p.ssdo_directions;
  s.ssdo_steps = p.ssdo_steps;
  s.ssgi_directions = p.ssgi_directions;
  s.ssgi_steps = p.ssgi_steps;
  s.sun_visibility = visibility_slot(s.shadow_filter);
}

}  // namespace

bool gow_unshadowed_local_lights(const Scene& scene, const Settings& s) {
  return scene.features().has(Feature::local_lights) && !s.params<GowRagnarokSettings>().local_lights;
}

Technique gow_ragnarok_technique() {
  Technique t;
  t.name = "gow-ragnarok";
  t.description =
      "visibility buffer, G-buffer, cascaded sun shadow maps with a dilated min/max early-out, PCF or "
      "contact-hardening shadows marched in shadow-map space (God of War Ragnarok)";
  t.passes = {{"visibility", make_visibility_pass},
              {"gbuffer", make_gbuffer_pass},
              {"shadow_maps", make_shadow_maps_pass},
              {"shadow_minmax", make_shadow_minmax_pass},
              {"shadows_pcf", make_shadows_pcf_pass},
              {"shadows_contact_hardening", make_shadows_contact_hardening_pass},
              {"direct_lighting", make_direct_lighting_pass},
              {"ssdo", make_ssdo_pass},
              {"ssgi", make_ssgi_pass},
              {"ssdo_ssgi", make_ssdo_ssgi_pass},
              {"direct_aov", make_direct_aov_pass},
              {"cubemap_capture", make_cubemap_capture_pass},
              {"reflections_rt_cubemap", make_reflections_rt_cubemap_pass},
              {"reflections_resolve", make_reflections_resolve_pass}};
  t.output = "gow_radiance";
  // direct: sun through the shadow map, sky by rays, local lights through SSDO (their only
  // visibility, gow_ragnarok.md "The AOV contract"); indirect_diffuse: SSGI's one bounce;
  // reflection: glossy surfaces' specular lobe (gow_ragnarok.md "Reflections"; scenes with a
  // glossy material; not part of radiance, as the reference's).
  t.contract_aovs = {{"radiance", "gow_radiance"},
                     {"direct", "gow_direct"},
                     {"indirect_diffuse", "ssgi_indirect"},
                     {"reflection", "reflection"}};
  t.contract_aov_needs = {{"reflection", Feature::glossy}};
  t.stages = gow_ragnarok_stages();
  t.aovs = {"vbuffer",          "depth",         "gbuffer_albedo",   "gbuffer_normal",   "gbuffer_position",
            "gbuffer_emissive", "shadow_map",    "shadow_minmax",    "shadow_pcf",       "shadow_contact_hardening",
            "direct_light",     "ssdo_cone",     "ssdo_local_light", "ssgi_indirect",    "gow_direct",
            "reflection",       "reflection_trace", "reflection_cubemap"};
  {
    using namespace glsl;
    // The seed's debug colours: where each reflection sample's colour came from.
    t.stats = {{"reflection_screen", "share of reflection samples hit on screen by the screen-space trace (cyan)",
                "reflection_stats", kReflStatScreen, kReflStatSamples},
               {"reflection_bvh_screen", "share of reflection samples hit in the BVH and read from the screen (purple)",
                "reflection_stats", kReflStatBvhScreen, kReflStatSamples},
               {"reflection_cubemap", "share of reflection samples read from the cube map (yellow)", "reflection_stats",
                kReflStatCubemap, kReflStatSamples},
               {"reflection_sky", "share of reflection samples whose BVH ray left the scene (the sky)",
                "reflection_stats", kReflStatSky, kReflStatSamples},
               {"reflection_masked", "share of reflection samples below the surface (weight 0)", "reflection_stats",
                kReflStatMasked, kReflStatSamples}};
  }
  define_settings<GowRagnarokSettings>(t, kPresets, apply_row);
  TechniqueOption filter{"shadow_filter", "sun shadows: 0 PCF (the baseline), 1 contact hardening", 0, 1, true};
  filter.apply = [](Settings& s, double v) {
    auto& g = s.params<GowRagnarokSettings>();
    g.shadow_filter = uint32_t(v);
    g.sun_visibility = visibility_slot(g.shadow_filter);
  };
  filter.read = [](const Settings& s) { return double(s.params<GowRagnarokSettings>().shadow_filter); };
  using G = GowRagnarokSettings;
  t.options = with_common_options(
      {
          option("sky_rays", "sky visibility rays per pixel (0: no sky light)", 0, 4294967295.0,
                 &DirectLightingParams::sky_rays),
          filter,
          direct_light_option(),
          option("cascades", "shadow cascades", 1, 4, &G::shadow_cascades),
          option("shadow_resolution", "texels per side of one cascade (rounded up to 8)", 64, 8192, &G::shadow_resolution),
          option("shadow_distance", "view distance (m) the last cascade ends at", 0.1, 1e5, &G::shadow_distance),
          option("split_lambda", "cascade splits: 1 logarithmic, 0 uniform", 0, 1, &G::shadow_split_lambda),
          option("caster_range", "metres towards the sun beyond a cascade that still cast", 0, 1e5, &G::shadow_caster_range),
          option("filter_radius", "area-light radius (m); 0: the sun's angular radius seen from march_distance", 0, 100,
                 &G::shadow_filter_radius),
          option("march_distance", "distance (m) of the area light the rays march to (seed: 2)", 0.01, 100,
                 &G::shadow_march_distance),
          option("shadow_bias", "depth bias (m) along the sun (too large: light leaks under objects)", 0, 100,
                 &G::shadow_bias),
          option("normal_offset", "receiver offset along its normal (shadow-map texels)", 0, 16, &G::shadow_normal_offset),
          option("taps", "PCF taps / contact-hardening rays per pixel", 1, 32, &G::shadow_taps),
          option("march_steps", "contact-hardening steps over the march distance", 1, 256, &G::shadow_march_steps),
          option("cascade_blend",
                 "seam band: within this fraction of a cascade's width from its edge, the shadow filters blend into "
                 "the next cascade (0: off, the hard seam)",
                 0, 0.5, &G::shadow_cascade_blend),
          option("minmax_early_out", "skip fully lit / shadowed pixels and shorten marches by the dilated min/max", 0, 1,
                 &G::shadow_minmax_early_out),
          option("local_shadows", "local lights: 1 shadow rays (direct_lighting), 0 no shadow maps (ssdo occludes them)",
                 0, 1, &DirectLightingParams::local_lights),
          option("ss_combined",
                 "SSDO and SSGI: 1 one pass sharing G-buffer reads and marches (ssdo_ssgi, as shipped), 0 the separate "
                 "ssdo and ssgi passes",
                 0, 1, &G::ss_combined),
          option("ss_history", "frames ssdo_ssgi's temporal accumulation averages at most (1: this frame alone)", 1,
                 glsl::kSsMaxHistory, &G::ss_history),
          option("ss_cone",
                 "ssdo_ssgi writes the debug view ssdo_cone (bent normal, open fraction; scenes with unshadowed "
                 "local lights): 0 not written, 1 written (8 bytes a pixel)",
                 0, 1, &G::ss_cone),
          option("ssdo", "screen-space directional occlusion of the unshadowed local lights (0: they leak)", 0, 1,
                 &G::ssdo),
          option("ssdo_radius", "metres ssdo marches per direction", 0.01, 100, &G::ssdo_radius),
          option("ssdo_thickness", "metres a surface in front of ssdo's march may be and still block it", 0.001, 100,
                 &G::ssdo_thickness),
          option("ssdo_directions", "ssdo directions per pixel", 1, glsl::kSsMaxDirections, &G::ssdo_directions),
          option("ssdo_steps", "ssdo steps per direction", 1, glsl::kSsMaxSteps, &G::ssdo_steps),
          option("ssgi", "screen-space one-bounce indirect light (0: none)", 0, 1, &G::ssgi),
          option("ssgi_radius", "metres ssgi marches per direction", 0.01, 100, &G::ssgi_radius),
          option("ssgi_thickness", "metres a surface in front of ssgi's march may be and still be its hit", 0.001, 100,
                 &G::ssgi_thickness),
          option("ssgi_directions", "ssgi directions per pixel", 1, glsl::kSsMaxDirections, &G::ssgi_directions),
          option("ssgi_steps", "ssgi steps per direction", 1, glsl::kSsMaxSteps, &G::ssgi_steps),
          option("reflection_mode", "glossy reflections: 0 the parallax-corrected cube map alone (baseline), 1 ray-traced "
                 "cube maps (screen, then BVH, then cube map)", 0, 1, &G::reflection_mode),
          option("cubemap_size", "texels per side of a reflection cube-map face", 4, 512, &G::cubemap_size),
          option("cubemap_bounces", "path vertices of the cube map's baked light", 1, 64, &G::cubemap_bounces),
          option("ssr_steps", "screen-space steps per reflection ray (0: BVH only)", 0, 1024, &G::ssr_steps),
          option("ssr_thickness", "m behind the depth buffer a screen-space hit may lie", 0, 100, &G::ssr_thickness),
          option("reflection_distance", "m a reflection ray marches on screen", 0.01, 1e5, &G::reflection_distance),
          option("reflection_history", "frames the reflections' temporal resolve averages at most", 1, 4096,
                 &G::reflection_history),
      },
      {0, 1});
  return t;
}

}  // namespace gib
