// Scene features: derived from a scene (Scene::features()), required by passes (PassDecl::needs).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace gib {

enum class Feature : uint32_t {
  sun = 1u << 0,
  sky = 1u << 1,
  local_lights = 1u << 2,
  emissive = 1u << 3,
  alpha_tested = 1u << 4,
  translucent = 1u << 5,
  textured = 1u << 6,
  motion = 1u << 7,
  decals = 1u << 8,  // projected decals (Scene::decals) with some opacity
  cloth = 1u << 9,   // a material of the cloth BRDF class
  indoor_volumes = 1u << 10,  // Scene::indoor_volumes (probe-volume's indoor/outdoor classes)
  glossy = 1u << 11,          // a material of the glossy BRDF class (a GGX specular layer)
};
inline constexpr uint32_t kFeatureCount = 12;

struct SceneFeatures {
  uint32_t bits = 0;
  constexpr SceneFeatures() = default;
  constexpr SceneFeatures(Feature f) : bits(static_cast<uint32_t>(f)) {}
  constexpr bool has(Feature f) const { return (bits & static_cast<uint32_t>(f)) != 0; }
  constexpr bool contains(SceneFeatures o) const { return (bits & o.bits) == o.bits; }
  constexpr SceneFeatures missing_from(SceneFeatures available) const {
    SceneFeatures r; r.bits = bits & ~available.bits; return r;
  }
  constexpr bool empty() const { return bits == 0; }
  constexpr SceneFeatures& operator|=(SceneFeatures o) { bits |= o.bits; return *this; }
  friend constexpr SceneFeatures operator|(SceneFeatures a, SceneFeatures b) { a |= b; return a; }
  friend constexpr bool operator==(SceneFeatures a, SceneFeatures b) { return a.bits == b.bits; }
};

std::string_view feature_name(Feature f);
std::string to_string(SceneFeatures f);  // "sun,sky" or "none"

}  // namespace gib
