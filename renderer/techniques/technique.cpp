#include "renderer/techniques/technique.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/passes/pass_list.h"

namespace gib {

const std::vector<Technique>& techniques() {
  static const std::vector<Technique> t = {
      {"direct", "visibility buffer, G-buffer, direct light from sun, sky and local lights with ray-traced shadows",
       {"visibility", "gbuffer", "direct_lighting"}, "direct_light",
       {"vbuffer", "depth", "gbuffer_albedo", "gbuffer_normal", "gbuffer_position", "gbuffer_emissive"},
       {"low", "medium", "high", "ultra"}},
      {"reference", "progressive path tracer (ground truth)", {"path_trace", "path_trace_resolve"}, "radiance",
       {"direct", "indirect_diffuse"}, {"low", "medium", "high", "ultra"}},
      {"radiance-cache",
       "idTech 8 GI: light grid, cascaded irradiance volumes, world radiance cache, 1/2-1/4 res final gather, "
       "bilateral denoise, upscale + temporal filter (renderer/techniques/radiance_cache.md)",
       {"visibility", "gbuffer", "direct_lighting", "light_grid", "probe_trace", "radiance_cache_update",
        "radiance_cache_shade", "irradiance_volume_update", "exposure", "final_gather", "gi_denoise", "gi_upscale", "composite"},
       "final_color",
       {"indirect_diffuse", "gi_irradiance", "direct_light", "probe_irradiance", "probe_visibility", "gather_sh_r",
        "gbuffer_albedo", "gbuffer_normal", "gbuffer_position"},
       {"low", "medium", "high", "ultra"}},
  };
  return t;
}

const Technique& find_technique(const std::string& name) {
  std::vector<std::string> names;
  for (auto& t : techniques()) {
    if (t.name == name) return t;
    names.push_back(t.name);
  }
  throw std::invalid_argument(fmt::format("--technique: expected one of [{}], got '{}'", fmt::join(names, ", "), name));
}

Settings apply_preset(const Technique& t, const std::string& preset, Settings s) {
  static const char* kPresets[] = {"low", "medium", "high", "ultra"};
  int level = -1;
  for (int i = 0; i < 4; ++i)
    if (preset == kPresets[i]) level = i;
  if (level < 0) throw std::invalid_argument(fmt::format("preset: expected low|medium|high|ultra, got '{}'", preset));
  s.preset = preset;
  if (t.name == "direct") {
    static const uint32_t kSkyRays[] = {1, 4, 16, 64};
    s.sky_rays = kSkyRays[level];
  } else if (t.name == "reference") {
    static const uint32_t kBounces[] = {4, 8, 16, 64};
    s.max_bounces = kBounces[level];
  } else if (t.name == "radiance-cache") {
    // The seed's platform tiers: 16/32/64 rays per probe, 1/4 or 1/2 gather; cascades and
    // cache size grow with quality (6 cascades and ~2^20 cells ship on consoles at 'ultra').
    static const uint32_t kRays[] = {16, 32, 64, 64};
    static const uint32_t kGather[] = {4, 2, 2, 2};
    static const uint32_t kCascades[] = {2, 3, 4, 6};
    static const uint32_t kCacheLog2[] = {13, 15, 16, 18};
    s.rc.rays_per_probe = kRays[level];
    s.rc.gather_divisor = kGather[level];
    s.rc.cascades = kCascades[level];
    s.rc.cache_log2_cells = kCacheLog2[level];
    // The sky reaches surfaces through the GI (gather misses return it, in the SH), so
    // direct_lighting must not add it again.
    s.sky_rays = 0;
  }
  return s;
}

std::vector<std::unique_ptr<Pass>> make_passes(const Technique& t) {
  std::vector<std::unique_ptr<Pass>> out;
  for (auto& p : t.passes) out.push_back(make_pass(p));
  return out;
}

namespace {
std::string option_value_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}
#define GIB_UINT_OPTION(field) [](Settings& s, double v) { field = static_cast<uint32_t>(v); }
#define GIB_FLOAT_OPTION(field) [](Settings& s, double v) { field = static_cast<float>(v); }
#define GIB_BOOL_OPTION(field) [](Settings& s, double v) { field = v != 0.0; }

// Options every technique shares: the NaN guards and the NaN-injection debug switches, the
// injection targets limited to those the technique's passes write; the world offset.
std::vector<TechniqueOption> with_debug_options(std::vector<TechniqueOption> opts, std::vector<double> targets) {
  opts.push_back({"nan_guards",
                  "drop or repair non-finite values wherever history is read, blended or accumulated (0/1; 0 is "
                  "the negative control of NaN injection)",
                  0, 1, true, GIB_BOOL_OPTION(s.nan_guards)});
  opts.push_back({"inject_nan",
                  "debug: write a NaN on frame inject_frame into 0 nothing, 1 the gbuffer_normal texel at "
                  "(inject_x, inject_y), 2 the radiance-cache cell of that pixel's surface, 3 the path tracer's "
                  "sample at that pixel",
                  0, 3, true, GIB_UINT_OPTION(s.debug.inject_nan), std::move(targets)});
  opts.push_back({"inject_frame", "debug: frame index (0-based) of the NaN injection", 0, 4294967295.0, true,
                  GIB_UINT_OPTION(s.debug.inject_frame)});
  opts.push_back({"inject_x", "debug: pixel column of the NaN injection", 0, 65535, true,
                  GIB_UINT_OPTION(s.debug.inject_x)});
  opts.push_back({"inject_y", "debug: pixel row of the NaN injection", 0, 65535, true,
                  GIB_UINT_OPTION(s.debug.inject_y)});
  // The far-from-origin stress: the whole scene and the camera moved (Settings::world_offset).
  opts.push_back({"world_offset_x", "metres added to every world-space x (scene, lights, camera)", -1e6, 1e6,
                  false, GIB_FLOAT_OPTION(s.world_offset.x)});
  opts.push_back({"world_offset_y", "metres added to every world-space y (scene, lights, camera)", -1e6, 1e6,
                  false, GIB_FLOAT_OPTION(s.world_offset.y)});
  opts.push_back({"world_offset_z", "metres added to every world-space z (scene, lights, camera)", -1e6, 1e6,
                  false, GIB_FLOAT_OPTION(s.world_offset.z)});
  return opts;
}
}  // namespace

const std::vector<TechniqueOption>& technique_options(const Technique& t) {
  static const std::vector<TechniqueOption> kDirect = with_debug_options(
      {
          {"sky_rays", "sky visibility rays per pixel (0: no sky light)", 0, 4294967295.0, true,
           GIB_UINT_OPTION(s.sky_rays)},
      },
      {0, 1});
  static const std::vector<TechniqueOption> kReference = with_debug_options({
      {"max_bounces", "path length cap (1: direct light only, no interreflection)", 1, 4294967295.0, true,
       GIB_UINT_OPTION(s.max_bounces)},
      {"spp_per_frame", "samples per pixel added each frame", 1, 4294967295.0, true, GIB_UINT_OPTION(s.spp_per_frame)},
  }, {0, 3});
  static const std::vector<TechniqueOption> kRadianceCache = with_debug_options({
      {"visibility_test", "leak mitigation: Chebyshev test on probe distance moments (0/1)", 0, 1, true,
       GIB_BOOL_OPTION(s.rc.visibility_test)},
      {"normal_bias", "leak mitigation: metres along the normal before sampling probes", 0, 10, false,
       GIB_FLOAT_OPTION(s.rc.normal_bias)},
      {"view_bias", "leak mitigation: metres towards the viewer before sampling probes", 0, 10, false,
       GIB_FLOAT_OPTION(s.rc.view_bias)},
      {"probe_rays",
       "leak mitigation: a shadow ray from each point that samples the volumes to each of its 8 probes; "
       "blocked probes get no weight (0/1)",
       0, 1, true, GIB_BOOL_OPTION(s.rc.probe_rays)},
      {"cache_side_key", "leak mitigation: radiance-cache cells keyed by surface side (0/1)", 0, 1, true,
       GIB_BOOL_OPTION(s.rc.cache_side_key)},
      {"disocclusion", "temporal filter rejects history failing depth/normal tests (0/1)", 0, 1, true,
       GIB_BOOL_OPTION(s.rc.disocclusion)},
      {"history_format", "GI history: 0 RGB9E5, 1 RGBA16F, 2 R11G11B10F, 3 RGBA32F", 0, 3, true,
       GIB_UINT_OPTION(s.rc.history_format)},
      {"history_max_frames", "n_max of the temporal filter", 1, 1024, true, GIB_UINT_OPTION(s.rc.history_max_frames)},
      {"cascades", "irradiance-volume cascades", 1, 8, true, GIB_UINT_OPTION(s.rc.cascades)},
      {"rays_per_probe", "visibility rays per updated probe", 1, 64, true, GIB_UINT_OPTION(s.rc.rays_per_probe)},
      {"probe_spacing", "metres between cascade-0 probes", 0.01, 100, false, GIB_FLOAT_OPTION(s.rc.probe_spacing)},
      {"gather_divisor", "final gather at 1/2 or 1/4 resolution (2 or 4)", 2, 4, true,
       GIB_UINT_OPTION(s.rc.gather_divisor)},
      {"cache_log2_cells", "radiance cache capacity, log2 cells", 4, 24, true, GIB_UINT_OPTION(s.rc.cache_log2_cells)},
      {"cache_reuse_frames", "frames a shaded cache cell is reused", 1, 1024, true,
       GIB_UINT_OPTION(s.rc.cache_reuse_frames)},
      {"denoise_radius", "bilateral half-width in gather pixels (0: off)", 0, 16, true,
       GIB_UINT_OPTION(s.rc.denoise_radius)},
      {"probe_hysteresis", "weight of last frame's probe texel when blending (0: no history)", 0, 0.999, false,
       GIB_FLOAT_OPTION(s.rc.probe_hysteresis)},
      {"multi_bounce",
       "1: caches feed back on themselves (cells and volumes shade bounces from last frame's volumes, the "
       "gather reads last frame's image); 0: single bounce (white-furnace negative control)",
       0, 1, true, GIB_BOOL_OPTION(s.rc.multi_bounce)},
      {"pre_exposure",
       "1: the gather, denoise and upscale work on radiance x P, P = 1 / log-average luminance of the frame "
       "(exposure pass), so RGBA16F SH and the history do not clamp under bright light; 0: P = 1 (negative control)",
       0, 1, true, GIB_BOOL_OPTION(s.rc.pre_exposure)},
  }, {0, 1, 2});
  static const std::vector<TechniqueOption> kNone;
  if (t.name == "direct") return kDirect;
  if (t.name == "reference") return kReference;
  if (t.name == "radiance-cache") return kRadianceCache;
  return kNone;
}

std::string check_option(const Technique& t, const std::string& name, double value) {
  const auto& opts = technique_options(t);
  for (const auto& o : opts) {
    if (o.name != name) continue;
    if (!std::isfinite(value) || (o.integer && value != std::floor(value)) || value < o.min || value > o.max)
      return fmt::format("expected {} in [{}, {}], got {}", o.integer ? "an integer" : "a number", o.min, o.max,
                         option_value_text(value));
    if (!o.allowed.empty() && std::find(o.allowed.begin(), o.allowed.end(), value) == o.allowed.end())
      return fmt::format("expected one of [{}] for {}, got {}", fmt::join(o.allowed, ", "), t.name,
                         option_value_text(value));
    return "";
  }
  std::vector<std::string> names;
  for (const auto& o : opts) names.push_back(o.name);
  return fmt::format("expected one of the options of {} ({}), got unknown option \"{}\"", t.name,
                     names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", ")), name);
}

Settings apply_options(const Technique& t, Settings s, const std::map<std::string, double>& options) {
  for (const auto& [name, value] : options) {
    std::string err = check_option(t, name, value);
    if (!err.empty()) throw std::invalid_argument(fmt::format("option \"{}\": {}", name, err));
    for (const auto& o : technique_options(t))
      if (o.name == name && o.apply) o.apply(s, value);
  }
  return s;
}

}  // namespace gib
