#include "renderer/techniques/probe_volume/probe_volume_stages.h"

#include <array>
#include <cstring>

#include "renderer/codecs/ycocg_sh.h"
#include "renderer/techniques/stage_oracles.h"

namespace gib {

namespace {

using oracles::Bytes;
using oracles::floats_to_bytes;
using oracles::seed_bytes;

std::map<std::string, Bytes> probes_oracle(const OracleInputs& in) {
  return {{"probe_irradiance", oracles::mean_halves(in, "probe_irradiance")},
          {"probe_radiance", oracles::mean_halves(in, "probe_radiance")}};
}

// pixel_denoise writes Y (Y0, Y1) and C (Co, Cg, frames, view depth; the upscale reads Co, Cg):
// the seeds' mean of the decoded per-pixel SH.
std::map<std::string, Bytes> denoise_oracle(const OracleInputs& in) {
  const size_t texels = seed_bytes(in, 0, "pixel_sh").size() / 8;
  std::vector<float> y(texels * 4, 0.0f), c(texels * 4, 0.0f);
  const float k = float(in.seeds.size());
  for (size_t s = 0; s < in.seeds.size(); ++s) {
    const Bytes& b = seed_bytes(in, s, "pixel_sh");
    for (size_t i = 0; i < texels; ++i) {
      std::array<uint32_t, 2> w;
      std::memcpy(w.data(), &b[i * 8], 8);
      const codecs::YcocgSh v = codecs::unpack_ycocg_sh(w);
      for (int j = 0; j < 4; ++j) y[i * 4 + j] += v[j] / k;
      c[i * 4 + 0] += v[4] / k;
      c[i * 4 + 1] += v[5] / k;
    }
  }
  return {{"pixel_gi_y", floats_to_bytes(y)}, {"pixel_gi_c", floats_to_bytes(c)}};
}

}  // namespace

std::vector<TechniqueStage> probe_volume_stages() {
  std::vector<TechniqueStage> s(4);
  s[0].name = "probes";
  s[0].passes = {"probe_select", "probe_classify", "probe_gbuffer", "probe_relight", "probe_convolve",
                 "probe_relocate"};
  s[0].oracle = "converged: the seed renders' mean probe_irradiance and probe_radiance";
  s[0].after_pass = "probe_convolve";
  s[0].seed_reads = {"probe_irradiance", "probe_radiance"};
  s[0].make = probes_oracle;
  s[1].name = "pixel_trace";
  s[1].passes = {"screen_trace", "world_trace", "hit_lighting"};
  s[2].name = "denoise";
  s[2].passes = {"pixel_denoise"};
  s[2].oracle = "the seed renders' mean of its input (pixel_sh, decoded)";
  s[2].after_pass = "pixel_denoise";
  s[2].seed_reads = {"pixel_sh"};
  s[2].make = denoise_oracle;
  s[3] = oracles::exact_gi_irradiance_stage("upscale", {"pixel_upscale"}, "pixel_upscale");
  return s;
}

}  // namespace gib
