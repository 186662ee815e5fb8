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
  // The cascaded shadow map's settings (cascades, resolution, bias, taps, march steps, ...) are
  // SunShadowParams, a base of DirectLightingParams (renderer/passes/sun_shadow_params.h).
  // Screen-space terms (ssdo/, ssgi/; gow_ragnarok.md "SSDO and SSGI"). Local lights have no
  // shadow maps (DirectLightingParams::local_lights false, option local_shadows 0): ssdo lights
  // them through its directional occlusion.
  bool ss_combined = true;           // ssdo_ssgi (one pass, as shipped); false: the separate ssdo and ssgi passes
  uint32_t ss_history = 16;          // ssdo_ssgi: frames its temporal accumulation averages at most (1: none)
  bool ss_cone = false;              // ssdo_ssgi writes the ssdo_cone debug view (8 bytes a pixel)
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
