// direct_lighting: lights every G-buffer pixel from the sun (one shadow ray per pixel into a
// cone of the sun's angular radius), the sky and emissive surfaces (`sky_rays` cosine-distributed
// rays: the sky where one escapes, the emission of what it hits) and every local light (point
// and spot, one shadow ray each; left to another pass where DirectLightingParams::local_lights is
// false), plus emission: the `direct` AOV of the contract
// (renderer/techniques/aov.h) exactly, for every light type. Lambertian, with
// diffuse transmission for translucent materials (light from the back face scaled by
// translucency). Sky pixels get the sky radiance. Output is linear HDR (RGBA32F).
// Slots: reads gbuffer_albedo, gbuffer_normal, gbuffer_position, gbuffer_emissive (and the slot
// named by DirectLightingParams::sun_visibility, where set and the scene has a sun); writes direct_light.
// Seed: the `direct` base technique (docs/architecture.md "Techniques"); shadows are traced with our BVH (god-of-war
// PCF/contact-hardening shadows are a later pass).
// Limits: loops over all local lights (the light grid of radiance-cache will bound this);
// specular terms are not shaded (roughness/metalness are stored but the BRDF is Lambertian).
// NaN guard (Settings::nan_guards): a non-finite G-buffer normal is lit as if it faced the camera.
#pragma once
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "renderer/graph/pass.h"

namespace gib {

// Settings of direct_lighting: the settings struct of every technique that runs it derives
// from this (the pass reads Settings::params<DirectLightingParams>()).
struct DirectLightingParams {
  uint32_t sky_rays = 4;  // cosine rays per pixel for sky and emissive-surface light (0: neither)
  // Empty: the sun is shadowed by a ray per pixel. Else the name of a slot (r32_float, render
  // size, visibility in [0, 1]) another pass of the technique writes: the sun light is scaled by
  // it instead of traced (a shadow-map technique's filtered shadows), from the sun's centre.
  std::string_view sun_visibility;
  // false: direct_lighting leaves the local lights out; another pass of the technique lights
  // them (gow-ragnarok's ssdo: lights without shadow maps, occluded in screen space).
  bool local_lights = true;
};

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

// The slots of a pass that lights the G-buffer into direct_light (direct_lighting and any pass
// sharing its code, renderer/passes/direct_lighting/direct_light.glsl).
std::vector<Slot> direct_light_slots(const ResourceDesc& out);

std::unique_ptr<Pass> make_direct_lighting_pass();
}  // namespace gib
