#include "renderer/techniques/gow_ragnarok/gow_ragnarok_stages.h"

#include "renderer/techniques/stage_oracles.h"

namespace gib {

namespace {
using oracles::Bytes;
using oracles::reference_rgba16f;
using oracles::reference_rgba32f;
}  // namespace

std::vector<TechniqueStage> gow_ragnarok_stages() {
  std::vector<TechniqueStage> s(3);
  s[0].name = "direct";
  s[0].passes = {"shadow_maps", "shadow_minmax", "shadows_pcf", "shadows_contact_hardening", "direct_lighting"};
  s[0].oracle = "exact: the reference's direct AOV (direct_light, the bounce source)";
  s[0].after_pass = "direct_lighting";
  s[0].reference_aovs = {"direct"};
  s[0].make = [](const OracleInputs& in) {
    return std::map<std::string, Bytes>{{"direct_light", reference_rgba32f(in, "direct")}};
  };
  s[1].name = "ssgi";
  s[1].passes = {"ssdo", "ssgi", "ssdo_ssgi"};
  s[1].oracle = "exact: the reference's indirect_diffuse (ssgi_indirect after the combined pass, in its format)";
  s[1].after_pass = "ssdo_ssgi";
  s[1].seed_reads = {"ssgi_indirect"};
  s[1].reference_aovs = {"indirect_diffuse"};
  s[1].make = [](const OracleInputs& in) {
    // RGBA16F from the combined pass (its history), RGBA32F from the separate ssgi pass.
    const Bytes& seed = oracles::seed_bytes(in, 0, "ssgi_indirect");
    const bool halves = in.formats.at("ssgi_indirect") == Format::rgba16_float;
    return std::map<std::string, Bytes>{{"ssgi_indirect", halves ? reference_rgba16f(in, "indirect_diffuse", &seed)
                                                                  : reference_rgba32f(in, "indirect_diffuse", &seed)}};
  };
  s[2].name = "reflections";
  s[2].passes = {"cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"};
  return s;
}

}  // namespace gib
