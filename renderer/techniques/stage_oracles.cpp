#include "renderer/techniques/stage_oracles.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "renderer/codecs/half.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/graph/executor.h"

namespace gib::oracles {

const Bytes& seed_bytes(const OracleInputs& in, size_t seed, const std::string& name) {
  auto it = in.seeds.at(seed).find(name);
  if (it == in.seeds[seed].end()) throw std::runtime_error(fmt::format("stage oracle: no '{}' read", name));
  return it->second;
}

namespace {

// The seeds' mean of `name`, read and written `Size` bytes per value through decode / encode;
// seed s's values times seed_scale[s] when given.
template <size_t Size, class Word, class Decode, class Encode>
Bytes mean_of(const OracleInputs& in, const std::string& name, Decode decode, Encode encode,
              const std::vector<double>& seed_scale = {}) {
  if (!seed_scale.empty() && seed_scale.size() != in.seeds.size())
    throw std::runtime_error(fmt::format("stage oracle: '{}': expected a scale per seed", name));
  const size_t values = seed_bytes(in, 0, name).size() / Size;
  constexpr size_t kChannels = std::tuple_size_v<decltype(decode(Word{}))>;
  std::vector<double> sum(values * kChannels, 0.0);
  for (size_t s = 0; s < in.seeds.size(); ++s) {
    const Bytes& b = seed_bytes(in, s, name);
    if (b.size() != values * Size) throw std::runtime_error(fmt::format("stage oracle: '{}' differs in size", name));
    for (size_t i = 0; i < values; ++i) {
      Word w;
      std::memcpy(&w, &b[i * Size], Size);
      const auto v = decode(w);
      for (size_t c = 0; c < kChannels; ++c)
        sum[i * kChannels + c] += seed_scale.empty() ? double(v[c]) : double(v[c]) * seed_scale[s];
    }
  }
  Bytes out(values * Size);
  const double k = double(in.seeds.size());
  for (size_t i = 0; i < values; ++i) {
    std::array<float, kChannels> m;
    for (size_t c = 0; c < kChannels; ++c) m[c] = float(sum[i * kChannels + c] / k);
    const Word w = encode(m);
    std::memcpy(&out[i * Size], &w, Size);
  }
  return out;
}

}  // namespace

Bytes mean_halves(const OracleInputs& in, const std::string& name, const std::vector<double>& seed_scale) {
  return mean_of<2, uint16_t>(
      in, name, [](uint16_t h) { return std::array<float, 1>{codecs::half_to_float(h)}; },
      [](const std::array<float, 1>& m) { return codecs::float_to_half(m[0]); }, seed_scale);
}

Bytes mean_floats(const OracleInputs& in, const std::string& name) {
  return mean_of<4, float>(
      in, name, [](float f) { return std::array<float, 1>{f}; }, [](const std::array<float, 1>& m) { return m[0]; });
}

Bytes mean_rgb9e5(const OracleInputs& in, const std::string& name) {
  return mean_of<4, uint32_t>(
      in, name,
      [](uint32_t w) {
        std::array<float, 3> v;
        codecs::decode_rgb9e5(w, v.data());
        return v;
      },
      [](const std::array<float, 3>& m) { return codecs::encode_rgb9e5(m.data()); });
}

Bytes floats_to_bytes(const std::vector<float>& v) {
  Bytes b(v.size() * 4);
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

Bytes reference_rgba32f(const OracleInputs& in, const std::string& aov, const Bytes* alpha_from) {
  const FloatImage& ref = in.reference.at(aov);
  if (ref.width != in.width || ref.height != in.height)
    throw std::runtime_error(fmt::format("stage oracle: expected a {}x{} reference '{}', got {}x{}", in.width,
                                         in.height, aov, ref.width, ref.height));
  const size_t n = size_t(in.width) * in.height;
  if (alpha_from && alpha_from->size() != n * 16)
    throw std::runtime_error("stage oracle: expected an RGBA32F render-size image to keep the alpha of");
  std::vector<float> v(n * 4, 1.0f);
  for (uint32_t y = 0; y < in.height; ++y)
    for (uint32_t x = 0; x < in.width; ++x) {
      const size_t i = size_t(y) * in.width + x;
      for (uint32_t ch = 0; ch < 3; ++ch) v[i * 4 + ch] = ref.at(x, y, ch);
      if (alpha_from) std::memcpy(&v[i * 4 + 3], &(*alpha_from)[i * 16 + 12], 4);
    }
  return floats_to_bytes(v);
}

Bytes reference_rgba16f(const OracleInputs& in, const std::string& aov, const Bytes* alpha_from) {
  const size_t n = size_t(in.width) * in.height;
  if (alpha_from && alpha_from->size() != n * 8)
    throw std::runtime_error("stage oracle: expected an RGBA16F render-size image to keep the alpha of");
  const Bytes full = reference_rgba32f(in, aov);
  std::vector<float> v(n * 4);
  std::memcpy(v.data(), full.data(), full.size());
  std::vector<uint16_t> h(n * 4);
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t ch = 0; ch < 3; ++ch)
      h[i * 4 + ch] = codecs::float_to_half(std::clamp(v[i * 4 + ch], -codecs::kHalfMax, codecs::kHalfMax));
    if (alpha_from)
      std::memcpy(&h[i * 4 + 3], &(*alpha_from)[i * 8 + 6], 2);
    else
      h[i * 4 + 3] = codecs::float_to_half(1.0f);
  }
  Bytes b(h.size() * 2);
  std::memcpy(b.data(), h.data(), b.size());
  return b;
}

std::map<std::string, Bytes> exact_gi_irradiance(const OracleInputs& in) {
  const FloatImage& ref = in.reference.at("indirect_diffuse");
  const auto [w, h] = in.extents.at("gbuffer_albedo");
  const FloatImage albedo = decode_texels(in.formats.at("gbuffer_albedo"), w, h, seed_bytes(in, 0, "gbuffer_albedo"));
  if (ref.width != w || ref.height != h)
    throw std::runtime_error(
        fmt::format("stage oracle: expected a {}x{} reference, got {}x{}", w, h, ref.width, ref.height));
  std::vector<float> e(size_t(w) * h * 4, 0.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t ch = 0; ch < 3; ++ch) {
        const float a = albedo.at(x, y, ch);
        e[(size_t(y) * w + x) * 4 + ch] = a > 0.0f ? ref.at(x, y, ch) / a : 0.0f;
      }
  return {{"gi_irradiance", floats_to_bytes(e)}};
}

TechniqueStage exact_gi_irradiance_stage(std::string name, std::vector<std::string> passes, std::string after_pass) {
  TechniqueStage s;
  s.name = std::move(name);
  s.passes = std::move(passes);
  s.oracle = "exact: the reference's indirect_diffuse over the G-buffer albedo (gi_irradiance)";
  s.after_pass = std::move(after_pass);
  s.seed_reads = {"gbuffer_albedo"};
  s.reference_aovs = {"indirect_diffuse"};
  s.make = exact_gi_irradiance;
  return s;
}

}  // namespace gib::oracles
