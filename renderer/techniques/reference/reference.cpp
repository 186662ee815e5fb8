// `reference`: the progressive unbiased path tracer every error is measured against
// (docs/architecture.md, "reference").
#include "renderer/techniques/reference/reference.h"

#include "renderer/techniques/reference/path_trace/path_trace.h"
#include "renderer/techniques/reference/path_trace_resolve/path_trace_resolve.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {
struct Preset {
  const char* name;
  uint32_t max_bounces;
};
constexpr Preset kPresets[] = {{"low", 4}, {"medium", 8}, {"high", 16}, {"ultra", 64}};
void apply_preset_row(ReferenceSettings& s, const Preset& p) { s.max_bounces = p.max_bounces; }
}  // namespace

Technique reference_technique() {
  Technique t;
  t.name = "reference";
  t.description = "progressive path tracer (ground truth)";
  t.passes = {{"path_trace", make_path_trace_pass}, {"path_trace_resolve", make_path_trace_resolve_pass}};
  t.output = "radiance";
  t.aovs = {"direct", "indirect_diffuse", "reflection"};
  t.contract_aovs = {{"direct", "direct"}, {"indirect_diffuse", "indirect_diffuse"}, {"reflection", "reflection"}};
  // reflection is 0 without a glossy material: references of such scenes keep no file of it.
  t.contract_aov_needs = {{"reflection", Feature::glossy}};
  define_settings<ReferenceSettings>(t, kPresets, apply_preset_row);
  t.options = with_common_options(
      {
          option("max_bounces", "path length cap (1: direct light only, no interreflection)", 1, 4294967295.0,
                 &ReferenceSettings::max_bounces),
          option("spp_per_frame", "samples per pixel added each frame", 1, 4294967295.0,
                 &ReferenceSettings::spp_per_frame),
          option("glossy_masking",
                 "1: the glossy BRDF's specular lobe with Smith masking-shadowing; 0: without (G = 1, which "
                 "gains energy at grazing angles: the glossy furnace's negative control)",
                 0, 1, &ReferenceSettings::glossy_masking),
      },
      {0, 3});
  return t;
}

}  // namespace gib
