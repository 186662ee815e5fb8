// Builds the push-constant block every probe-volume pass shares from Settings, and the sizes of
// the probe buffers (C++ only).
#pragma once
#include <fmt/format.h>

#include <cstdint>

#include "renderer/graph/pass.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
#include "renderer/techniques/probe_volume/probe_volume.h"

namespace gib {

static_assert(sizeof(glsl::PvParams) == 80, "PvParams: 80 bytes in every probe-volume push block");
static_assert(sizeof(glsl::PvProbe) == 96 && sizeof(glsl::PvCascade) == 32 && sizeof(glsl::PvSelection) == 48 && sizeof(glsl::PvTexelLists) == 32,
              "probe-volume buffer structs: std430 sizes");

inline uint32_t pv_probe_count(const ProbeVolumeSettings& p) { return p.cascades * p.grid_xz * p.grid_xz * p.grid_y; }

// Throws GraphError naming the setting when the volume cannot be built.
inline void check_pv_settings(const ProbeVolumeSettings& p) {
  if (p.cascades == 0 || p.cascades > glsl::kPvMaxCascades)
    throw GraphError(fmt::format("probe-volume: cascades must be 1..{}, got {}", glsl::kPvMaxCascades, p.cascades));
  if (p.grid_xz < 2 || p.grid_y < 2 || p.grid_xz > 64 || p.grid_y > 64)
    throw GraphError(fmt::format("probe-volume: grid_xz and grid_y must be 2..64, got {} and {}", p.grid_xz, p.grid_y));
  if (p.probe_budget == 0) throw GraphError("probe-volume: probe_budget must be at least 1");
  if (p.pixel_divisor != 1 && p.pixel_divisor != 2)
    throw GraphError(fmt::format("probe-volume: pixel_divisor must be 1 or 2, got {}", p.pixel_divisor));
}

inline glsl::PvParams make_pv_params(const Settings& s, uint32_t frame) {
  const ProbeVolumeSettings& p = s.params<ProbeVolumeSettings>();
  using namespace glsl;
  uint32_t flags = (s.nan_guards ? kPvFlagNanGuards : 0) | (p.multi_bounce ? kPvFlagMultiBounce : 0) |
                   (p.lighting_scale ? kPvFlagLightingScale : 0) | (p.visibility_test ? kPvFlagVisibility : 0) |
                   (p.inverse_ray_offset ? kPvFlagInverseRay : 0) | (p.probe_ao ? kPvFlagProbeAo : 0) |
                   (p.relocation ? kPvFlagRelocation : 0) | (p.material_mask ? kPvFlagMaterialMask : 0) |
                   (p.translucent_rays ? kPvFlagTranslucentRays : 0) | (p.quarter_res_new ? kPvFlagQuarterNew : 0) |
                   (p.indoor_classes ? kPvFlagIndoor : 0) | (p.lookup_view ? kPvFlagLookupView : 0);
  PvParams r{};
  r.grid = {p.grid_xz, p.grid_y, p.cascades, frame};
  r.volume = {p.probe_spacing, p.forward_offset, p.trace_range, p.pixel_range};
  r.sampling = {p.normal_offset, p.view_offset, p.nearest_weight, p.gbuffer_share};
  r.flags = {flags, p.probe_budget, p.pixel_divisor, p.denoise_radius | (p.history_max_frames << 16)};
  r.pixel = {p.min_start, 0, 0, 0};
  return r;
}

// The per-pixel rays' resolution (pixel_divisor 1: full, 2: half width and height) and how many
// ray pixels a frame has.
inline SizeRule pv_pixel_size(const ProbeVolumeSettings& p) { return p.pixel_divisor == 1 ? SizeRule::render : SizeRule::half; }
inline double pv_ray_pixels(const Settings& s) {
  const uint32_t d = s.params<ProbeVolumeSettings>().pixel_divisor;
  return double(s.width) * s.height / (d * d);
}

// A buffer resource of `bytes` (persistent: kept across frames, e.g. the per-probe caches).
inline ResourceDesc pv_buffer(uint64_t bytes, bool persistent) {
  ResourceDesc b{Format::buffer, SizeRule::buffer};
  b.bytes = bytes;
  b.persistent = persistent;
  return b;
}

// Bytes of the probe buffers (probe_volume_shared.h).
inline uint64_t pv_state_bytes(const ProbeVolumeSettings& p) {
  return glsl::kPvMaxCascades * sizeof(glsl::PvCascade) + uint64_t(pv_probe_count(p)) * sizeof(glsl::PvProbe);
}
inline uint64_t pv_selection_bytes(const ProbeVolumeSettings& p) {
  return sizeof(glsl::PvSelection) + uint64_t(p.probe_budget) * 4;
}

}  // namespace gib
