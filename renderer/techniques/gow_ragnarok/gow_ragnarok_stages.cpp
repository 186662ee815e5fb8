#include "renderer/techniques/gow_ragnarok/gow_ragnarok_stages.h"

#include <fmt/format.h>

#include <cstring>
#include <stdexcept>

#include "renderer/techniques/stage_oracles.h"

namespace gib {

namespace {

using oracles::Bytes;

// `aov` of the reference as RGBA32F texels; alpha from `alpha_from` (same size) or 1.
Bytes reference_rgba32f(const OracleInputs& in, const std::string& aov, const Bytes* alpha_from) {
  const FloatImage& ref = in.reference.at(aov);
  if (ref.width != in.width || ref.height != in.height)
    throw std::runtime_error(fmt::format("gow-ragnarok oracle: expected a {}x{} reference '{}', got {}x{}", in.width,
                                         in.height, aov, ref.width, ref.height));
  const size_t n = size_t(in.width) * in.height;
  if (alpha_from && alpha_from->size() != n * 16)
    throw std::runtime_error("gow-ragnarok oracle: expected an RGBA32F render-size image to keep the alpha of");
  std::vector<float> v(n * 4, 1.0f);
  for (uint32_t y = 0; y < in.height; ++y)
    for (uint32_t x = 0; x < in.width; ++x) {
      const size_t i = size_t(y) * in.width + x;
      for (uint32_t ch = 0; ch < 3; ++ch) v[i * 4 + ch] = ref.at(x, y, ch);
      if (alpha_from) std::memcpy(&v[i * 4 + 3], &(*alpha_from)[i * 16 + 12], 4);
    }
  return oracles::floats_to_bytes(v);
}

}  // namespace

std::vector<TechniqueStage> gow_ragnarok_stages() {
  std::vector<TechniqueStage> s(3);
  s[0].name = "direct";
  s[0].passes = {"shadow_maps", "shadow_minmax", "shadows_pcf", "shadows_contact_hardening", "direct_lighting"};
  s[0].oracle = "exact: the reference's direct AOV (direct_light, the bounce source)";
  s[0].after_pass = "direct_lighting";
  s[0].reference_aovs = {"direct"};
  s[0].make = [](const OracleInputs& in) {
    return std::map<std::string, Bytes>{{"direct_light", reference_rgba32f(in, "direct", nullptr)}};
  };
  s[1].name = "ssgi";
  s[1].passes = {"ssdo", "ssgi", "ssdo_ssgi"};
  s[1].oracle = "exact: the reference's indirect_diffuse (ssgi_indirect after the combined pass)";
  s[1].after_pass = "ssdo_ssgi";
  s[1].seed_reads = {"ssgi_indirect"};
  s[1].reference_aovs = {"indirect_diffuse"};
  s[1].make = [](const OracleInputs& in) {
    return std::map<std::string, Bytes>{
        {"ssgi_indirect", reference_rgba32f(in, "indirect_diffuse", &oracles::seed_bytes(in, 0, "ssgi_indirect"))}};
  };
  s[2].name = "reflections";
  s[2].passes = {"cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"};
  return s;
}

}  // namespace gib
