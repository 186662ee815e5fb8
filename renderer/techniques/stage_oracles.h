// Building blocks of the stage oracles (TechniqueStage::make) that error attribution writes over
// a stage's outputs: the seed renders' mean of a resource in its own encoding (a converged
// oracle: the representation kept, one seed's noise removed), and the exact oracle of the shared
// composite's input (the reference's indirect_diffuse over the G-buffer albedo).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib::oracles {

using Bytes = std::vector<uint8_t>;

// Seed `seed`'s read of `name`; an error naming the resource if the render did not read it.
const Bytes& seed_bytes(const OracleInputs& in, size_t seed, const std::string& name);

// The seeds' mean of a resource stored as 16-bit halves, 32-bit floats or RGB9E5 words (each
// rounded back to its encoding; RGB9E5 by round to nearest). mean_halves: seed s's values times
// seed_scale[s] when given (one per seed).
Bytes mean_halves(const OracleInputs& in, const std::string& name, const std::vector<double>& seed_scale = {});
Bytes mean_floats(const OracleInputs& in, const std::string& name);
Bytes mean_rgb9e5(const OracleInputs& in, const std::string& name);

Bytes floats_to_bytes(const std::vector<float>& v);

// The reference's `aov` as render-size RGBA32F texels; alpha 1, or that of `alpha_from` (an
// RGBA32F render-size image) when given. An error when the reference is another size.
Bytes reference_rgba32f(const OracleInputs& in, const std::string& aov, const Bytes* alpha_from = nullptr);
// The same as RGBA16F texels (each channel rounded to nearest, clamped to the half's largest
// value as a history store clamps it); alpha 1, or that of `alpha_from` (RGBA16F, render size).
Bytes reference_rgba16f(const OracleInputs& in, const std::string& aov, const Bytes* alpha_from = nullptr);

// gi_irradiance (rgba32f, E / pi) that makes the shared composite's indirect_diffuse the
// reference's: the reference indirect_diffuse over the G-buffer albedo, 0 where the albedo is.
std::map<std::string, Bytes> exact_gi_irradiance(const OracleInputs& in);

// A stage whose oracle is exact_gi_irradiance, written after `after_pass`.
TechniqueStage exact_gi_irradiance_stage(std::string name, std::vector<std::string> passes, std::string after_pass);

}  // namespace gib::oracles
