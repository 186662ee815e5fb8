// direct_lighting: lights every G-buffer pixel from the sun (one shadow ray per pixel into a
// cone of the sun's angular radius), the sky and emissive surfaces (`sky_rays` cosine-distributed
// rays: the sky where one escapes, the emission of what it hits) and every local light (point
// and spot, one shadow ray each; left to another pass where DirectLightingParams::local_lights is
// false), plus emission: the `direct` AOV of the contract
// (renderer/techniques/aov.h) exactly, for every light type. Lambertian, with
// diffuse transmission for translucent materials (light from the back face scaled by
// translucency). Sky pixels get the sky radiance. Output is linear HDR (RGBA32F).
// Slots: reads gbuffer_albedo, gbuffer_normal, gbuffer_position, gbuffer_emissive (and, where
// the scene has a sun, the slot sun_visibility_slot() names: DirectLightingParams::sun_visibility,
// or shadow_pcf in the shadow_mapped mode); writes direct_light.
// Seed: the `direct` base technique (docs/architecture.md "Techniques"); traced mode: shadows and
// sky through our BVH; shadow_mapped mode: the sun through the shared cascaded shadow map
// (docs/architecture.md "Direct light modes").
// Limits: loops over all local lights (the light grid of radiance-cache will bound this);
// specular terms are not shaded (roughness/metalness are stored but the BRDF is Lambertian).
// NaN guard (Settings::nan_guards): a non-finite G-buffer normal is lit as if it faced the camera.
#pragma once
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "renderer/graph/pass.h"
#include "renderer/passes/sun_shadow_params.h"

namespace gib {

// How the sun and the sky reach the G-buffer (option `direct_light`).
//   traced: the sun by a shadow ray per pixel, sky and emissive light by `sky_rays` rays through
//     the BVH: the reference's light paths, which the accuracy checks need.
//   shadow_mapped: as a shipped game lights them: the sun through the cascaded shadow map
//     (shadow_maps, shadow_minmax, shadows_pcf; or the technique's own filter, sun_visibility),
//     the sky unoccluded (the same `sky_rays` cosine directions, evaluated without a ray), and
//     emissive surfaces left to the technique's GI: no BVH walk for sun or sky. Local lights keep
//     their shadow rays (no local shadow maps). docs/architecture.md "Direct light modes".
enum class DirectLightMode : uint32_t { traced = 0, shadow_mapped = 1 };

// Settings of direct_lighting: the settings struct of every technique that runs it derives
// from this (the pass reads Settings::params<DirectLightingParams>()). The shadow map's
// settings (SunShadowParams) come with it, for the shadow_mapped mode.
struct DirectLightingParams : SunShadowParams {
  uint32_t sky_rays = 4;  // cosine rays per pixel for sky and emissive-surface light (0: neither)
  // Empty: the sun is shadowed by a ray per pixel. Else the name of a slot (r32_float, render
  // size, visibility in [0, 1]) another pass of the technique writes: the sun light is scaled by
  // it instead of traced (a shadow-map technique's filtered shadows), from the sun's centre.
  std::string_view sun_visibility;
  // false: direct_lighting leaves the local lights out; another pass of the technique lights
  // them (gow-ragnarok's ssdo: lights without shadow maps, occluded in screen space).
  bool local_lights = true;
  uint32_t direct_light = uint32_t(DirectLightMode::traced);  // DirectLightMode
};

// The slot the sun's visibility is read from: DirectLightingParams::sun_visibility where the
// technique names one, else shadows_pcf's output in the shadow_mapped mode, else "" (traced).
std::string_view sun_visibility_slot(const DirectLightingParams& p);
// The shadow_mapped mode: sky light unoccluded, emissive surfaces not sampled (no sky rays).
inline bool sky_unoccluded(const DirectLightingParams& p) {
  return p.direct_light == uint32_t(DirectLightMode::shadow_mapped);
}

// The sky-ray ladder of every technique whose quality is direct_lighting's (direct, deferred).
struct SkyRaysPreset {
  const char* name;
  uint32_t sky_rays;
};
inline constexpr SkyRaysPreset kSkyRaysPresets[] = {{"low", 1}, {"medium", 4}, {"high", 16}, {"ultra", 64}};
template <class Settings>
void apply_sky_rays_preset(Settings& s, const SkyRaysPreset& row) {
  static_cast<DirectLightingParams&>(s).sky_rays = row.sky_rays;
}

// Whether the lighting walks the BVH: the traced mode, or shadow rays of local lights.
bool walks_bvh(const Scene& scene, const DirectLightingParams& p);

// The slots of a pass that lights the G-buffer into direct_light (direct_lighting and any pass
// sharing its code, renderer/passes/direct_lighting/direct_light.glsl).
std::vector<Slot> direct_light_slots(const ResourceDesc& out);

std::unique_ptr<Pass> make_direct_lighting_pass();
}  // namespace gib
