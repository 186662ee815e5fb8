// Builds the push-constant block every radiance-cache pass shares from Settings (C++ only).
#pragma once
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"

namespace gib {

// Probes per irradiance-volume cascade (16^3); one cascade is updated per frame.
inline constexpr uint32_t kProbesPerCascade = glsl::kProbeGridDim * glsl::kProbeGridDim * glsl::kProbeGridDim;

// The cascade whose probes frame `frame` traces and updates. Schedule 0: each in turn
// (frame % cascades). Schedule 1 (high, ultra): the finest on even frames, the others in turn on
// odd frames, so the finest cascade (the surroundings of the camera) is updated every other
// frame however many cascades there are, and cascade c > 0 every 2 (cascades - 1) frames.
inline uint32_t rc_updated_cascade(uint32_t schedule, uint32_t cascades, uint32_t frame) {
  if (cascades <= 1) return 0;
  if (schedule == 0 || cascades == 2) return frame % cascades;
  return frame % 2 == 0 ? 0 : 1 + (frame / 2) % (cascades - 1);
}

// Probe hit records per frame: one per ray of the updated cascade.
inline uint32_t rc_hit_records(const Settings& s) {
  return kProbesPerCascade * s.params<RadianceCacheSettings>().rays_per_probe;
}
// Entries of the active-cell list (rc_active): one per ray at most (kRcActivePerProbe, or
// rays_per_probe if larger), so it cannot overflow (a cell is queued at most once per frame).
uint32_t rc_active_capacity(const Settings& s);
// The insertion's counters summed per workgroup in shared memory (option update_counters: 0 by
// device: GPUs yes, CPU devices no, where a group barrier costs more than the atomics).
inline bool rc_group_counts(const DeviceInfo& info, const RadianceCacheSettings& r) {
  return r.update_counters == 0 ? !info.is_software() : r.update_counters == 1;
}

static_assert(sizeof(glsl::RcParams) == 80, "RcParams: 80 bytes in every radiance-cache push block");

inline glsl::RcParams make_rc_params(const Settings& s, uint32_t frame) {
  const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
  glsl::RcParams p{};
  p.grid = {r.probe_spacing, float(r.cascades), float(r.rays_per_probe), float(rc_updated_cascade(r.probe_schedule, r.cascades, frame))};
  p.cache = {r.cache_cell_size, r.cache_lod_distance, float(r.cache_log2_cells), float(r.cache_max_probe)};
  p.bias = {r.normal_bias, r.view_bias, r.visibility_test ? 1.0f : 0.0f, r.probe_hysteresis};
  p.misc = {frame, r.cache_reuse_frames, gather_divisor(r), r.light_grid_cascades};
  p.flags = {(r.cache_side_key ? glsl::kRcFlagSideKey : 0u) | (r.inside_test ? glsl::kRcFlagInsideTest : 0u), s.nan_guards ? 1u : 0u, r.multi_bounce ? 1u : 0u, r.probe_rays ? 1u : 0u};
  return p;
}

}  // namespace gib
