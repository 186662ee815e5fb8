// The `probe-volume` technique's settings (definition: probe_volume.cpp; design notes:
// probe_volume.md). Presets and case options set them; its passes read them with
// Settings::params<ProbeVolumeSettings>().
#pragma once
#include <cstdint>

#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"

namespace gib {

struct ProbeVolumeSettings : TechniqueSettingsOf<ProbeVolumeSettings>, DirectLightingParams {
  // Sky and emissive surfaces reach the first visible surface through direct_lighting's sky
  // rays (the AOV contract's `direct`); the per-pixel rays carry bounce light only.
  ProbeVolumeSettings() { sky_rays = 4; }
  // ---- probe volume (AC Shadows "Probe volume": 5 cascades of 16x16x8, 2-32 m)
  uint32_t cascades = 5;
  uint32_t grid_xz = 16;            // probes along x and z per cascade
  uint32_t grid_y = 8;              // probes along y (up)
  float probe_spacing = 2.0f;       // metres between cascade-0 probes; doubles per cascade
  float forward_offset = 0.25f;     // the volume's centre sits this fraction of its width ahead of the camera
  uint32_t probe_budget = 1024;     // probes updated per frame (512 / 1024 by preset)
  float gbuffer_share = 0.16f;      // share of the budget left after new probes that re-traces G-buffers
  bool quarter_res_new = true;      // new probes trace 10x10 of their 20x20 texels (replicated 2x2)
  float trace_range = 4.0f;         // probe rays reach this many cascade spacings
  bool multi_bounce = true;         // probe hits add last frame's probe irradiance (0: single bounce)
  bool lighting_scale = true;       // unselected probes are rescaled by the sun/sky change (0: control)
  // ---- sampling (AC Shadows "Light leaks: probe filtering")
  bool visibility_test = true;      // Chebyshev test on the 8-bit depth moments
  float normal_offset = 0.2f;       // cascade spacings along the normal before sampling
  float view_offset = 0.1f;         // cascade spacings towards the viewer
  bool inverse_ray_offset = true;   // back along the incoming ray, at most half its length
  bool probe_ao = true;             // darken irradiance where the ray is shorter than a spacing
  bool relocation = true;           // probe_relocate moves probes out of / away from geometry
  bool indoor_classes = true;       // probes blend only with points of their class (indoor volumes of the scene)
  float nearest_weight = 0.9f;      // nearest-probe fast path when its trilinear weight exceeds this (> 1: off)
  bool lookup_view = false;         // diagnostic: per-pixel rays replaced by the probe lookup at the pixel's surface
  // ---- per pixel (AC Shadows "Per-pixel diffuse algorithm")
  uint32_t pixel_divisor = 2;       // rays traced at 1/2 (quarter resolution) or 1 (full)
  uint32_t screen_steps = 24;       // screen_trace steps per ray (0: every ray in the BVH)
  float screen_thickness = 0.1f;    // metres behind the depth buffer a screen hit may be
  bool screen_resume = false;       // world rays resume from the last visible point (the seed's; leaks at silhouettes)
  float pixel_range = 2.0f;         // per-pixel rays reach this many times the probe trace range
  // Per-pixel rays skip this many metres first (the seed's 0.05 against self-intersection; ours
  // start from an offset origin and need none: 0.05 lets rays from a room's corners skip the
  // adjacent wall's face and leak in light from behind it: extreme-range's interior 1e5x).
  float min_start = 0.0f;
  uint32_t denoise_radius = 2;      // spatial filter half-width (quarter-res pixels; 0: off)
  uint32_t history_max_frames = 16; // temporal filter n_max (1: no history)
  float anti_lag_sigma = 3.0f;      // slow history clamped to the fast one +- this many std devs of their difference (0: off)
  uint32_t fast_history_frames = 4; // the anti-lag's fast history n_max
  bool material_mask = true;        // spatial filter keeps translucent and opaque pixels apart
  bool translucent_rays = true;     // per-pixel rays on translucent surfaces may take the back side
};

}  // namespace gib
