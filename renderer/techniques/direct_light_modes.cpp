#include "renderer/techniques/direct_light_modes.h"

#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/passes/shadow_maps/shadow_maps.h"
#include "renderer/passes/shadow_minmax/shadow_minmax.h"
#include "renderer/passes/shadows_pcf/shadows_pcf.h"

namespace gib {

std::vector<PassEntry> sun_shadow_passes() {
  return {{"shadow_maps", make_shadow_maps_pass},
          {"shadow_minmax", make_shadow_minmax_pass},
          {"shadows_pcf", make_shadows_pcf_pass}};
}

TechniqueOption direct_light_option() {
  return option("direct_light",
                "sun and sky: 0 traced (a shadow ray and sky rays per pixel through the BVH, the reference's light "
                "paths), 1 shadow_mapped (the sun through cascaded shadow maps and PCF, the sky unoccluded, emissive "
                "surfaces left to GI: a shipped game's cost)",
                0, 1, &DirectLightingParams::direct_light);
}

std::vector<TechniqueOption> direct_light_options() {
  using P = DirectLightingParams;
  return {direct_light_option(),
          option("shadow_resolution", "shadow_mapped: texels per side of one cascade (rounded up to 8)", 64, 8192,
                 &P::shadow_resolution),
          option("shadow_cascades", "shadow_mapped: sun shadow cascades", 1, 4, &P::shadow_cascades),
          option("shadow_distance", "shadow_mapped: view distance (m) the last cascade ends at", 0.1, 1e5,
                 &P::shadow_distance),
          option("shadow_bias", "shadow_mapped: depth bias (m) along the sun", 0, 100, &P::shadow_bias),
          option("shadow_normal_offset", "shadow_mapped: receiver offset along its normal (shadow-map texels)", 0, 16,
                 &P::shadow_normal_offset),
          option("shadow_taps", "shadow_mapped: PCF taps per pixel", 1, 32, &P::shadow_taps)};
}

void add_direct_light_modes(Technique& t) {
  for (PassEntry& p : sun_shadow_passes()) t.passes.push_back(std::move(p));
  for (TechniqueOption& o : direct_light_options()) t.options.push_back(std::move(o));
}

}  // namespace gib
