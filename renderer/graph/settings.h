// What a frame is rendered with: the settings every technique shares (size, seed, NaN guards,
// debug injection, world offset) and, held opaquely, the running technique's own settings
// struct. The graph layer knows no technique: a pass reads its technique's settings, typed,
// with `settings.params<RadianceCacheSettings>()` (or the parameter struct of a shared pass,
// e.g. DirectLightingParams, which a technique's settings struct derives from).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <typeinfo>

#include "renderer/scene/math.h"

namespace gib {

// Base of every technique's settings struct. Derive from TechniqueSettingsOf<YourSettings> (and
// from the parameter structs of the shared passes the technique runs).
struct TechniqueSettings {
  virtual ~TechniqueSettings() = default;
  virtual std::unique_ptr<TechniqueSettings> clone() const = 0;
};
template <class Derived>
struct TechniqueSettingsOf : TechniqueSettings {
  std::unique_ptr<TechniqueSettings> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
};

// Robustness debugging (technique options inject_nan, inject_frame, inject_x, inject_y): the pass
// that writes the target resource writes a NaN into it on one frame.
struct DebugSettings {
  uint32_t inject_nan = 0;    // 0 none, 1 gbuffer_normal texel (gbuffer), 2 radiance-cache cell radiance
                              // (radiance_cache_shade), 3 one path-tracer sample (path_trace)
  uint32_t inject_frame = 0;  // frame index (RecordContext::frame, 0-based) of the injection
  uint32_t inject_x = 0, inject_y = 0;  // pixel (render resolution); target 2: the cell of that pixel's surface
  bool injects(uint32_t target, uint32_t frame) const { return inject_nan == target && frame == inject_frame; }
};

// How ray traversals treat alpha-tested triangles (common options alpha_strategy and
// alpha_any_hit_limit; AC Shadows' alpha sampling study; renderer/shaders/include/
// alpha_strategy.glsl). Primary visibility (rasterised) always tests the mask.
enum class AlphaStrategy : uint32_t {
  test = 0,           // evaluate the mask at every candidate (the reference)
  dither = 1,         // the baked average opacity against a per-ray hash, no mask fetch
  opaque_approx = 2,  // triangles shrunk about their centroid to area x average opacity, opaque
  opaque = 3,         // alpha ignored: every card opaque (a negative control)
};
struct AlphaSettings {
  AlphaStrategy strategy = AlphaStrategy::test;
  uint32_t any_hit_limit = 0;  // > 0: after this many alpha-tested candidates a ray treats the rest as opaque
};

// Owns one TechniqueSettings; copies clone it, so Settings copies like a value.
class TechniqueSettingsHolder {
 public:
  TechniqueSettingsHolder() = default;
  explicit TechniqueSettingsHolder(std::unique_ptr<TechniqueSettings> p) : p_(std::move(p)) {}
  TechniqueSettingsHolder(const TechniqueSettingsHolder& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  TechniqueSettingsHolder(TechniqueSettingsHolder&&) noexcept = default;
  TechniqueSettingsHolder& operator=(const TechniqueSettingsHolder& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  TechniqueSettingsHolder& operator=(TechniqueSettingsHolder&&) noexcept = default;
  const TechniqueSettings* get() const { return p_.get(); }
  TechniqueSettings* get() { return p_.get(); }

 private:
  std::unique_ptr<TechniqueSettings> p_;
};

// Throws GraphError: "settings: a pass expected <wanted>, but the technique settings are <held>".
[[noreturn]] void throw_settings_type_error(const std::type_info& wanted, const TechniqueSettings* held);

struct Settings {
  uint32_t width = 256, height = 144;
  uint32_t seed = 1;
  std::string preset = "medium";
  // >= 0: every frame renders the scene at this time (seconds): a reference of one moment of
  // an animated scene. < 0: frame f renders at f * scene.frame_time.
  float scene_time = -1.0f;
  // Every pass that reads history, blends or accumulates drops/repairs non-finite values (and
  // gib_surface/gbuffer/direct_lighting repair non-finite normals). 0 turns them all off (negative control).
  bool nan_guards = true;
  // Metres added to every world-space position (vertices, lights, camera position and target)
  // when the executor uploads the scene: the far-from-origin stress case (options
  // world_offset_x/y/z). The image is unchanged in exact arithmetic.
  Vec3 world_offset{0, 0, 0};
  AlphaSettings alpha;
  // false: every material's translucency is 0 for this run (option `translucency`): the
  // technique without translucency support, AC Shadows' "missing contributions" image (a
  // negative control of translucent-paper).
  bool translucency = true;
  DebugSettings debug;

  // The technique whose settings struct `technique_settings` holds ("" before apply_preset /
  // apply_options gave it one: renderer/techniques/technique.h).
  std::string technique;

  // The technique's settings as P (its settings struct, or a shared pass's parameter struct it
  // derives from). Throws GraphError when the technique has none of that type.
  template <class P>
  const P& params() const {
    if (auto* p = dynamic_cast<const P*>(technique_settings_.get())) return *p;
    throw_settings_type_error(typeid(P), technique_settings_.get());
  }
  template <class P>
  P& params() {
    if (auto* p = dynamic_cast<P*>(technique_settings_.get())) return *p;
    throw_settings_type_error(typeid(P), technique_settings_.get());
  }
  template <class P>
  bool has_params() const {
    return dynamic_cast<const P*>(technique_settings_.get()) != nullptr;
  }
  const TechniqueSettings* technique_settings() const { return technique_settings_.get(); }
  void set_technique_settings(std::string name, std::unique_ptr<TechniqueSettings> t) {
    technique = std::move(name);
    technique_settings_ = TechniqueSettingsHolder(std::move(t));
  }

 private:
  TechniqueSettingsHolder technique_settings_;
};

}  // namespace gib
