#include "harness/tier.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/techniques/technique.h"

namespace gib {

Tier resolve_tier(const std::string& requested, const std::string& device_class) {
  if (requested == "ci") return Tier::ci;
  if (requested == "gpu") return Tier::gpu;
  if (!requested.empty())
    throw std::invalid_argument(fmt::format("--tier: expected ci or gpu, got '{}'", requested));
  return device_class == "lavapipe" ? Tier::ci : Tier::gpu;
}

const char* tier_name(Tier t) { return t == Tier::ci ? "ci" : "gpu"; }

namespace {

// Options that are pixel coordinates (TechniqueOption::pixel) name the same point of the image
// at w x h as at the case's CI size: the centre of the old pixel, in the new grid.
void scale_pixel_options(TechniqueRun& run, const Case& from, uint32_t w, uint32_t h) {
  const Technique& t = find_technique(run.technique);
  auto scale = [&](std::map<std::string, double>& options) {
    for (auto& [name, v] : options)
      for (const TechniqueOption& o : t.options) {
        if (o.name != name || o.pixel == TechniqueOption::Pixel::no) continue;
        const bool col = o.pixel == TechniqueOption::Pixel::column;
        const double size = col ? w : h, was = col ? from.width : from.height;
        v = std::min(size - 1, std::floor((v + 0.5) * size / was));
      }
  };
  scale(run.options);
  for (auto& [name, options] : run.variants) scale(options);
}

}  // namespace

Case at_tier(const Case& c, Tier t) {
  Case out = c;
  if (t == Tier::gpu) {
    out.width = c.gpu_width;
    out.height = c.gpu_height;
    for (TechniqueRun& r : out.techniques) scale_pixel_options(r, c, out.width, out.height);
    for (NegativeControl& nc : out.negative_controls) scale_pixel_options(nc.run, c, out.width, out.height);
  }
  return out;
}

GoldenStore technique_store(const std::string& goldens_dir, const std::string& case_name, Tier t) {
  if (t == Tier::ci) return GoldenStore(goldens_dir, case_name);
  GoldenStore s(goldens_dir, case_name, "gpu");
  s.set_write_half(true);
  return s;
}

}  // namespace gib
