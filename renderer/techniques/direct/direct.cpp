// `direct`: the base every GI technique adds to (docs/architecture.md, "direct"): visibility buffer,
// G-buffer, direct light with ray-traced shadows.
#include "renderer/techniques/direct/direct.h"

#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"

namespace gib {
Technique direct_technique() {
  Technique t;
  t.name = "direct";
  t.description = "visibility buffer, G-buffer, direct light from sun, sky and local lights with ray-traced shadows";
  t.passes = {{"visibility", make_visibility_pass},
              {"gbuffer", make_gbuffer_pass},
              {"direct_lighting", make_direct_lighting_pass}};
  t.output = "direct_light";
  // Only direct light: its output is the contract's `direct` exactly (and its radiance); it has
  // no indirect_diffuse to declare.
  t.contract_aovs = {{"direct", "direct_light"}};
  t.aovs = {"vbuffer", "depth", "gbuffer_albedo", "gbuffer_normal", "gbuffer_position", "gbuffer_emissive"};
  define_settings<DirectSettings>(t, kSkyRaysPresets, apply_sky_rays_preset<DirectSettings>);
  t.options = with_common_options(
      {
          option("sky_rays", "sky visibility rays per pixel (0: no sky light)", 0, 4294967295.0,
                 &DirectLightingParams::sky_rays),
      },
      {0, 1});
  add_direct_light_modes(t);  // option direct_light: traced or shadow_mapped
  return t;
}

}  // namespace gib
