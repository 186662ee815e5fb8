// The `radiance-cache` technique's settings (definition: radiance_cache.cpp; design notes:
// radiance_cache.md). Presets and case options set them; its passes read them with
// Settings::params<RadianceCacheSettings>().
#pragma once
#include <cstdint>

#include "renderer/graph/graph.h"
#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"

namespace gib {

struct RadianceCacheSettings : TechniqueSettingsOf<RadianceCacheSettings>, DirectLightingParams {
  // The sky and emissive surfaces reach surfaces through the final gather, which keeps that
  // part (the AOV contract's `direct`, renderer/techniques/aov.h) apart from bounce light, so
  // direct_lighting must not trace them again.
  RadianceCacheSettings() { sky_rays = 0; }
  uint32_t cascades = 3;            // irradiance-volume cascades (16^3 probes each), one updated per frame
  uint32_t probe_schedule = 0;      // 0: cascade frame % cascades; 1: the finest every other frame (rc_updated_cascade)
  float probe_spacing = 0.5f;       // metres between cascade-0 probes; doubles per cascade
  uint32_t rays_per_probe = 32;     // visibility rays per updated probe (16 / 32 / 64)
  float probe_hysteresis = 0.85f;   // weight of last frame's probe texel when blending
  uint32_t gather_divisor = 2;      // final gather at 1/1, 1/2 or 1/4 resolution (gather_divisor())
  uint32_t cache_log2_cells = 20;   // world radiance cache capacity (2^n cells; 2^20 x 16 B: the seed's 14 MB)
  uint32_t cache_max_probe = 8;     // linear-probing steps before an insertion is dropped
  float cache_cell_size = 0.25f;    // metres at LOD 0
  float cache_lod_distance = 8.0f;  // metres: LOD = 2^floor(log2(1 + dist / this))
  uint32_t cache_reuse_frames = 4;  // a shaded cell is reused this many frames
  uint32_t light_grid_cascades = 4; // 16^3 cells each, first cascade light_grid_extent metres wide
  float light_grid_extent = 32.0f;
  bool visibility_test = true;      // leak mitigation: Chebyshev test on RG16F probe moments
  float normal_bias = 0.1f;         // leak mitigation: metres along the normal before sampling probes
  float view_bias = 0.1f;           // leak mitigation: metres towards the viewer
  bool probe_rays = true;           // leak mitigation: a shadow ray from the sampled point to each of its 8 probes; blocked ones get no weight
  bool cache_side_key = true;       // leak mitigation: cache cells keyed by surface side, so the two faces of a thin wall differ
  bool inside_test = true;          // leak mitigation: probes inside geometry (solids' backs, surfaces < 1e-3 spacings) unused; see kRcFlagInsideTest
  bool disocclusion = true;         // temporal filter rejects history failing depth/normal tests
  uint32_t history_format = 0;      // 0 RGB9E5 (R32_UINT), 1 RGBA16F, 2 R11G11B10F, 3 RGBA32F
  uint32_t history_max_frames = 16; // n_max of the temporal filter
  uint32_t denoise_radius = 3;      // bilateral half-width in gather pixels
  uint32_t denoise_hit_weight = 0;  // gi_denoise: 1 = SH taps also weigh hit-distance similarity (the seed's; biased, radiance_cache.md)
  bool multi_bounce = true;         // 0: no cache feeds back on itself (single bounce; white-furnace negative control)
  bool dither_stores = false;       // RGB9E5 probe atlas and GI history round stochastically (unbiased blends)
  bool pre_exposure = true;         // screen-space GI works on radiance x P (exposure pass); 0: P = 1 (negative control)
  uint32_t volume_kernel = 0;       // irradiance_volume_update: 0 by device (GPU per-probe, CPU split), 1 per-probe, 2 split
  uint32_t volume_fallback = 0;     // per-probe volume kernel: 0 probes whose rays miss the cache run again in a fallback dispatch, 1 the fallback inline
  uint32_t insertion_rounds = 0;    // radiance_cache_update: 0 rounds 1 .. max_probe in one workgroup, 1 one indirect dispatch per round
  // gi_denoise: 0 one dispatch (radius <= 4, else as 2), 1 two per-tap dispatches, 2 two tiled
  // dispatches (radius <= 8, else as 1). Default 2: on the H200 (cornell, medium, Series S-scaled)
  // the one-dispatch form reads 1.337 ms against 0.890 ms for 2 (its tile, 11.8 KB, halves the
  // groups resident per SM); the output is the same bit for bit in every layout.
  uint32_t denoise_kernel = 2;
  uint32_t upscale_kernel = 0;      // gi_upscale: 0 the group's gather samples preloaded to shared memory, 1 each tap reads the images
  uint32_t insertion_find = 0;      // cache insertion round 0 (the find): 0 in probe_trace as it traces, 1 a dispatch of radiance_cache_update
  uint32_t update_counters = 0;     // radiance_cache_update's counters: 0 by device (GPU per workgroup, CPU per subgroup), 1 per workgroup, 2 per subgroup
};

// The gather's divisor as the passes use it: 1 (full resolution: ultra, beyond the seed), 2 or 4
// (the seed's 1/2 and 1/4); an option value of 3 reads as 2.
inline uint32_t gather_divisor(const RadianceCacheSettings& r) {
  return r.gather_divisor >= 4 ? 4u : r.gather_divisor <= 1 ? 1u : 2u;
}
// The size rule of the gather-resolution images (final_gather's SH, gi_denoise's).
inline SizeRule gather_size_rule(const RadianceCacheSettings& r) {
  const uint32_t d = gather_divisor(r);
  return d == 4 ? SizeRule::quarter : d == 2 ? SizeRule::half : SizeRule::render;
}

}  // namespace gib
