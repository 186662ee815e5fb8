// Builds the push-constant block every radiance-cache pass shares from Settings (C++ only).
#pragma once
#include <cmath>
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"

namespace gib {

// Probes per irradiance-volume cascade (16^3); one cascade is updated per frame.
inline constexpr uint32_t kProbesPerCascade = glsl::kProbeGridDim * glsl::kProbeGridDim * glsl::kProbeGridDim;

static_assert(sizeof(glsl::RcParams) == 80, "RcParams: 80 bytes in every radiance-cache push block");

inline glsl::RcParams make_rc_params(const Settings& s, uint32_t frame) {
  const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
  glsl::RcParams p{};
  p.grid = {r.probe_spacing, float(r.cascades), float(r.rays_per_probe), float(frame % r.cascades)};
  p.cache = {r.cache_cell_size, r.cache_lod_distance, float(r.cache_log2_cells), float(r.cache_max_probe)};
  p.bias = {r.normal_bias, r.view_bias, r.visibility_test ? 1.0f : 0.0f, r.probe_hysteresis};
  p.misc = {frame, r.cache_reuse_frames, r.gather_divisor, r.light_grid_cascades};
  p.flags = {r.cache_side_key ? 1u : 0u, s.nan_guards ? 1u : 0u, r.multi_bounce ? 1u : 0u, r.probe_rays ? 1u : 0u};
  return p;
}

// The work counters of the two cache passes: the table's cells and the probe hits of the one
// cascade updated per frame.
inline std::vector<WorkCounter> rc_cache_work(const Settings& s) {
  const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
  return {{"cache_cells", std::ldexp(1.0, int(r.cache_log2_cells))}, {"hits", double(kProbesPerCascade) * r.rays_per_probe}};
}

}  // namespace gib
