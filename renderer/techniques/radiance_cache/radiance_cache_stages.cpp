#include "renderer/techniques/radiance_cache/radiance_cache_stages.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "renderer/techniques/stage_oracles.h"

namespace gib {

namespace {

using oracles::Bytes;

std::map<std::string, Bytes> volumes_oracle(const OracleInputs& in) {
  return {{"probe_irradiance", oracles::mean_rgb9e5(in, "probe_irradiance")},
          {"probe_visibility", oracles::mean_halves(in, "probe_visibility")}};
}

float exposure_now(const Bytes& exposure) {
  float p;
  std::memcpy(&p, &exposure.at(size_t(glsl::kExposureNow) * 4), 4);
  return p;
}

// gi_denoise filters each gather image into its own output of the same size and format. The
// gather holds irradiance / pi x P (pre-exposure, P from the exposure pass, which follows the
// image): each read is brought to absolute units by its own P, averaged, and written at a fixed
// P, the reads' mean, which the oracle also writes into `exposure` (this frame's and last
// frame's P, after the exposure pass: the whole frame runs at that P) for gi_upscale. Without
// that, an oracle brighter than the technique lowers the next frame's P and gi_upscale divides
// the frozen values by it: a feedback that drifts.
std::map<std::string, Bytes> denoise_oracle(const OracleInputs& in) {
  std::vector<double> p(in.seeds.size());
  double p_sum = 0.0;
  for (size_t s = 0; s < in.seeds.size(); ++s) p_sum += p[s] = exposure_now(oracles::seed_bytes(in, s, "exposure"));
  const float p_fixed = float(p_sum / double(in.seeds.size()));
  std::vector<double> scale(in.seeds.size());
  for (size_t s = 0; s < in.seeds.size(); ++s) scale[s] = p_fixed / std::max(float(p[s]), 1e-30f);
  std::map<std::string, Bytes> out;
  for (const auto& [from, to] : {std::pair{"gather_sh_r", "gi_sh_r"}, std::pair{"gather_sh_g", "gi_sh_g"},
                                 std::pair{"gather_sh_b", "gi_sh_b"}, std::pair{"gather_direct", "gi_direct"}})
    out[to] = oracles::mean_halves(in, from, scale);
  Bytes exposure = oracles::seed_bytes(in, 0, "exposure");
  std::memcpy(&exposure.at(size_t(glsl::kExposureNow) * 4), &p_fixed, 4);
  std::memcpy(&exposure.at(size_t(glsl::kExposurePrev) * 4), &p_fixed, 4);
  out["exposure"] = exposure;
  return out;
}

// gi_composite writes indirect_diffuse = albedo x history / P, direct_radiance and final_color =
// their sum (alpha 1): the reference's indirect_diffuse in the first, and the seed renders' mean
// direct_radiance plus it in the last, so next frame's gather reads the same image too.
std::map<std::string, Bytes> composite_oracle(const OracleInputs& in) {
  Bytes indirect = oracles::reference_rgba32f(in, "indirect_diffuse");
  const Bytes direct = oracles::mean_floats(in, "direct_radiance");
  if (direct.size() != indirect.size())
    throw std::runtime_error("radiance-cache oracle: expected an RGBA32F render-size direct_radiance");
  Bytes color = indirect;
  for (size_t i = 0; i < color.size() / 4; ++i) {
    if (i % 4 == 3) continue;  // alpha 1, as gi_composite writes it
    float c, d;
    std::memcpy(&c, &color[i * 4], 4);
    std::memcpy(&d, &direct[i * 4], 4);
    c += d;
    std::memcpy(&color[i * 4], &c, 4);
  }
  return {{"indirect_diffuse", std::move(indirect)}, {"final_color", std::move(color)}};
}

}  // namespace

std::vector<TechniqueStage> radiance_cache_stages() {
  std::vector<TechniqueStage> s(5);
  s[0].name = "radiance_cache";
  s[0].passes = {"light_grid", "probe_trace", "radiance_cache_update", "radiance_cache_shade"};
  s[1].name = "irradiance_volumes";
  s[1].passes = {"irradiance_volume_update"};
  s[1].oracle = "converged: the seed renders' mean probe_irradiance (RGB9E5) and probe_visibility";
  s[1].after_pass = "irradiance_volume_update";
  s[1].seed_reads = {"probe_irradiance", "probe_visibility"};
  s[1].make = volumes_oracle;
  s[2].name = "final_gather";
  s[2].passes = {"exposure", "final_gather"};
  s[3].name = "denoise";
  s[3].passes = {"gi_denoise"};
  s[3].oracle = "the seed renders' mean of its input (gather_sh_r/g/b, gather_direct), at their mean pre-exposure";
  s[3].after_pass = "gi_denoise";
  s[3].seed_reads = {"gather_sh_r", "gather_sh_g", "gather_sh_b", "gather_direct", "exposure"};
  s[3].after_pass_of = {{"exposure", "exposure"}};  // the pass that writes it: the whole frame at that P
  s[3].make = denoise_oracle;
  s[4].name = "upscale";
  s[4].passes = {"gi_upscale", "gi_composite", "gi_resolve"};
  s[4].oracle = "exact: the reference's indirect_diffuse (and final_color = the seeds' mean direct_radiance + it)";
  s[4].after_pass = "gi_composite";
  s[4].seed_reads = {"direct_radiance"};
  s[4].reference_aovs = {"indirect_diffuse"};
  s[4].make = composite_oracle;
  return s;
}

}  // namespace gib
