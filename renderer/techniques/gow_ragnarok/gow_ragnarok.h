// The `gow-ragnarok` technique's settings (definition: gow_ragnarok.cpp, design: gow_ragnarok.md).
#pragma once
#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/techniques/gow_ragnarok/gow_reflection_params.h"

namespace gib {

enum class ShadowFilter : uint32_t { pcf = 0, contact_hardening = 1 };

struct GowRagnarokSettings : TechniqueSettingsOf<GowRagnarokSettings>, DirectLightingParams, GowReflectionParams {
  uint32_t shadow_filter = uint32_t(ShadowFilter::contact_hardening);
  uint32_t cascades = 3;             // 1..kShadowMaxCascades
  uint32_t shadow_resolution = 1024; // texels per side of one cascade (rounded up to kShadowMinMaxTile)
  float shadow_distance = 30.0f;     // far view distance (m) of the last cascade
  float split_lambda = 0.75f;        // cascade splits: 1 logarithmic, 0 uniform (the practical scheme)
  float caster_range = 50.0f;        // m towards the sun beyond a cascade's sphere that still casts
  float filter_radius = 0.0f;        // area-light radius (m); 0: the sun's angular radius seen from march_distance
  float march_distance = 2.0f;       // the seed's area light is 2 m from the pixel
  float shadow_bias = 0.02f;         // m along the sun direction
  float normal_offset = 1.0f;        // shadow-map texels along the normal
  uint32_t taps = 16;                // PCF taps / contact-hardening rays per pixel (1..32)
  uint32_t march_steps = 12;         // contact-hardening steps over the march distance
  bool minmax_early_out = true;      // shadow_minmax: skip fully lit / shadowed pixels, shorten marches
  GowRagnarokSettings() { sun_visibility = "shadow_contact_hardening"; }  // the selected filter's output
};

}  // namespace gib
