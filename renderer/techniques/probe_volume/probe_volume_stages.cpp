#include "renderer/techniques/probe_volume/probe_volume_stages.h"

#include <fmt/format.h>

#include <cstring>
#include <stdexcept>

#include "renderer/codecs/half.h"
#include "renderer/codecs/ycocg_sh.h"
#include "renderer/graph/executor.h"

namespace gib {

namespace {

using Bytes = std::vector<uint8_t>;

const Bytes& seed_bytes(const OracleInputs& in, size_t seed, const std::string& name) {
  auto it = in.seeds.at(seed).find(name);
  if (it == in.seeds[seed].end()) throw std::runtime_error(fmt::format("probe-volume oracle: no '{}' read", name));
  return it->second;
}

// The mean over the seeds of a buffer of half floats, rounded back to half.
Bytes mean_half_buffer(const OracleInputs& in, const std::string& name) {
  const size_t halves = seed_bytes(in, 0, name).size() / 2;
  std::vector<double> sum(halves, 0.0);
  for (size_t s = 0; s < in.seeds.size(); ++s) {
    const Bytes& b = seed_bytes(in, s, name);
    if (b.size() != halves * 2) throw std::runtime_error(fmt::format("probe-volume oracle: '{}' differs in size", name));
    for (size_t i = 0; i < halves; ++i) {
      uint16_t h;
      std::memcpy(&h, &b[i * 2], 2);
      sum[i] += codecs::half_to_float(h);
    }
  }
  Bytes out(halves * 2);
  for (size_t i = 0; i < halves; ++i) {
    const uint16_t h = codecs::float_to_half(float(sum[i] / double(in.seeds.size())));
    std::memcpy(&out[i * 2], &h, 2);
  }
  return out;
}

Bytes floats_to_bytes(const std::vector<float>& v) {
  Bytes b(v.size() * 4);
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

std::map<std::string, Bytes> probes_oracle(const OracleInputs& in) {
  return {{"probe_irradiance", mean_half_buffer(in, "probe_irradiance")},
          {"probe_radiance", mean_half_buffer(in, "probe_radiance")}};
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

// gi_irradiance holds E / pi, which composite multiplies by the albedo: the reference's
// indirect_diffuse over the albedo (0 where the albedo is).
std::map<std::string, Bytes> upscale_oracle(const OracleInputs& in) {
  const FloatImage& ref = in.reference.at("indirect_diffuse");
  const auto [w, h] = in.extents.at("gbuffer_albedo");
  const FloatImage albedo = decode_texels(in.formats.at("gbuffer_albedo"), w, h, seed_bytes(in, 0, "gbuffer_albedo"));
  if (ref.width != w || ref.height != h)
    throw std::runtime_error(fmt::format("probe-volume oracle: expected a {}x{} reference, got {}x{}", w, h, ref.width,
                                         ref.height));
  std::vector<float> e(size_t(w) * h * 4, 0.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t ch = 0; ch < 3; ++ch) {
        const float a = albedo.at(x, y, ch);
        e[(size_t(y) * w + x) * 4 + ch] = a > 0.0f ? ref.at(x, y, ch) / a : 0.0f;
      }
  return {{"gi_irradiance", floats_to_bytes(e)}};
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
  s[3].name = "upscale";
  s[3].passes = {"pixel_upscale"};
  s[3].oracle = "exact: the reference's indirect_diffuse over the G-buffer albedo";
  s[3].after_pass = "pixel_upscale";
  s[3].seed_reads = {"gbuffer_albedo"};
  s[3].reference_aovs = {"indirect_diffuse"};
  s[3].make = upscale_oracle;
  return s;
}

}  // namespace gib
