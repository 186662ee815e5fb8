// The settings of the cascaded sun shadow map (renderer/passes/shadow_maps/, shadow_minmax/,
// shadows_pcf/ and gow-ragnarok's shadows_contact_hardening): a base of DirectLightingParams, so
// every technique that runs direct_lighting has them and its `direct_light: shadow_mapped` mode
// can build the map (the passes read Settings::params<SunShadowParams>()).
#pragma once
#include <cstdint>

namespace gib {

struct SunShadowParams {
  uint32_t shadow_cascades = 3;        // 1..kShadowMaxCascades
  uint32_t shadow_resolution = 1024;   // texels per side of one cascade (rounded up to kShadowMinMaxTile)
  float shadow_distance = 30.0f;       // far view distance (m) of the last cascade
  float shadow_split_lambda = 0.75f;   // cascade splits: 1 logarithmic, 0 uniform (the practical scheme)
  float shadow_caster_range = 50.0f;   // m towards the sun beyond a cascade's sphere that still casts
  float shadow_filter_radius = 0.0f;   // area-light radius (m); 0: the sun's angular radius seen from shadow_march_distance
  float shadow_march_distance = 2.0f;  // the area light's distance from the pixel (gow-ragnarok's seed: 2 m)
  float shadow_bias = 0.02f;           // m along the sun direction
  float shadow_normal_offset = 1.0f;   // shadow-map texels along the normal
  uint32_t shadow_taps = 16;           // PCF taps / contact-hardening rays per pixel (1..32)
  uint32_t shadow_march_steps = 12;    // contact-hardening steps over the march distance
  bool shadow_minmax_early_out = true; // shadow_minmax: skip fully lit / shadowed pixels, shorten marches
  float shadow_cascade_blend = 0.1f;   // seam band (fraction of a cascade's width) blended into the next cascade; 0 off
};

}  // namespace gib
