// The `gow-ragnarok` technique's settings (definition: gow_ragnarok.cpp, design: gow_ragnarok.md).
#pragma once
#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/techniques/gow_ragnarok/gow_reflection_params.h"

namespace gib {

struct Scene;

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
  float cascade_blend = 0.1f;        // seam band (fraction of a cascade's width) blended into the next cascade; 0 off
  // Screen-space terms (ssdo/, ssgi/; gow_ragnarok.md "SSDO and SSGI"). Local lights have no
  // shadow maps (DirectLightingParams::local_lights false, option local_shadows 0): ssdo lights
  // them through its directional occlusion.
  bool ss_combined = true;           // ssdo_ssgi (one pass, as shipped); false: the separate ssdo and ssgi passes
  uint32_t ss_history = 16;          // ssdo_ssgi: frames its temporal accumulation averages at most (1: none)
  bool ssdo = true;                  // off: unshadowed local lights light everything in reach (the leak)
  float ssdo_radius = 1.0f;          // m marched per direction
  float ssdo_thickness = 1.0f;       // m: a depth-buffer surface nearer than this in front of the march blocks it
  uint32_t ssdo_directions = 8;      // cosine-weighted directions per pixel (1..kSsMaxDirections)
  uint32_t ssdo_steps = 6;           // steps per direction (1..kSsMaxSteps)
  bool ssgi = true;                  // off: no indirect light (indirect_diffuse 0)
  float ssgi_radius = 2.0f;
  float ssgi_thickness = 0.5f;
  uint32_t ssgi_directions = 8;
  uint32_t ssgi_steps = 12;
  GowRagnarokSettings() {
    sun_visibility = "shadow_contact_hardening";  // the selected filter's output
    local_lights = false;                         // unshadowed: ssdo lights them
  }
};

// The scene has local lights and direct_lighting leaves them to SSDO (local_shadows 0): ssdo
// (or ssdo_ssgi) lights them.
bool gow_unshadowed_local_lights(const Scene& scene, const Settings& s);

}  // namespace gib
