#include "harness/attribution/attribution.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gib::attribution {

namespace {

std::vector<double> game_of(const std::vector<RoiError>& subsets, double RoiError::*field) {
  std::vector<double> v;
  for (const RoiError& e : subsets) v.push_back(e.*field);
  return v;
}

// The stage with the largest share when it beats the next by 3x the noise floor; else -1.
// The mean of channel 0 over `rect`.
double rect_mean(const FloatImage& img, const metrics::PixelRect& rect) {
  double sum = 0;
  for (uint32_t y = rect.y_begin; y < rect.y_end; ++y)
    for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) sum += img.at(x, y, 0);
  return sum / double(rect.pixel_count());
}

int largest_resolved(const std::vector<StageBar>& bars, double noise_floor) {
  if (bars.empty()) return -1;
  std::vector<size_t> order(bars.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bars[a].shapley > bars[b].shapley; });
  if (!bars[order[0]].resolved) return -1;
  if (order.size() > 1 && bars[order[0]].shapley - bars[order[1]].shapley < 3.0 * noise_floor) return -1;
  return int(order[0]);
}

}  // namespace

Attribution attribute_renders(const std::vector<std::string>& stages,
                              const std::vector<std::vector<FloatImage>>& renders, const FloatImage& reference,
                              const std::vector<NamedRoi>& rois, const Options& options) {
  const uint32_t n = uint32_t(stages.size());
  if (n == 0 || n > kMaxStages)
    throw std::invalid_argument(fmt::format("attribution: expected 1..{} stages with an oracle, got {}", kMaxStages, n));
  if (renders.size() != (size_t(1) << n))
    throw std::invalid_argument(fmt::format("attribution: expected {} subsets of renders, got {}", 1u << n,
                                            renders.size()));
  Attribution out;
  out.stages = stages;
  out.seeds = uint32_t(renders[0].size());
  out.renders = uint32_t(renders.size() * out.seeds);
  const uint32_t all = (1u << n) - 1;
  std::vector<std::vector<FloatImage>> flip_maps;  // [mask][seed]
  if (options.flip_map)
    for (const auto& seeds : renders) {
      auto& maps = flip_maps.emplace_back();
      for (const FloatImage& img : seeds) maps.push_back(options.flip_map(img));
    }
  for (size_t r = 0; r < rois.size(); ++r) {
    RoiAttribution ra;
    ra.roi = rois[r].name;
    ra.noise_floor = r < options.noise_floor.size() ? options.noise_floor[r] : 0.0;
    const metrics::PixelRect rect = metrics::roi_pixels(rois[r].box, reference.width, reference.height);
    for (const auto& seeds : renders) ra.subsets.push_back(roi_error(seeds, reference, rect));
    ra.none = ra.subsets[0];
    ra.all = ra.subsets[all];
    const std::vector<double> mse = shapley(game_of(ra.subsets, &RoiError::mse), n);
    const std::vector<double> bias = shapley(game_of(ra.subsets, &RoiError::bias2), n);
    const std::vector<double> var = shapley(game_of(ra.subsets, &RoiError::variance), n);
    const std::vector<double> energy = shapley(game_of(ra.subsets, &RoiError::signed_energy), n);
    // Per-seed games (Shapley is linear in v: their mean is the bar) give the interval.
    std::vector<std::vector<double>> per_seed;
    for (uint32_t s = 0; s < out.seeds; ++s) {
      std::vector<double> v;
      for (const RoiError& e : ra.subsets) v.push_back(e.per_seed_mse[s]);
      per_seed.push_back(shapley(v, n));
    }
    for (uint32_t i = 0; i < n; ++i) {
      StageBar b;
      b.stage = stages[i];
      b.shapley = mse[i];
      b.bias_removed = bias[i];
      b.variance_removed = var[i];
      b.signed_energy = energy[i];  // v(S) - v(S + i): the stage's own share of the signed ratio
      b.pair = cheap_pair(game_of(ra.subsets, &RoiError::mse), n, i);
      if (out.seeds > 1) {
        double mean = 0, sq = 0;
        for (auto& p : per_seed) mean += p[i] / out.seeds;
        for (auto& p : per_seed) sq += (p[i] - mean) * (p[i] - mean);
        b.ci95 = 1.96 * std::sqrt(sq / (out.seeds - 1) / out.seeds);
      }
      b.resolved = std::abs(b.shapley) >= 3.0 * ra.noise_floor;
      ra.stages.push_back(b);
    }
    for (const auto& maps : flip_maps) {
      double sum = 0;
      for (const FloatImage& m : maps) sum += rect_mean(m, rect) / double(maps.size());
      ra.flip.push_back(sum);
    }
    if (!ra.flip.empty()) ra.flip_shapley = shapley(ra.flip, n);
    ra.floor_disagrees = ra.noise_floor > 0 && ra.all.mse > 3.0 * ra.noise_floor;
    ra.largest = largest_resolved(ra.stages, ra.noise_floor);
    out.rois.push_back(std::move(ra));
  }
  return out;
}

Attribution attribute(const std::vector<std::string>& stages, const RenderFn& render, const FloatImage& reference,
                      const std::vector<NamedRoi>& rois, const Options& options) {
  const uint32_t n = uint32_t(stages.size());
  if (n == 0 || n > kMaxStages)
    throw std::invalid_argument(fmt::format("attribution: expected 1..{} stages with an oracle, got {}", kMaxStages, n));
  if (options.seeds == 0) throw std::invalid_argument("attribution: expected --seeds >= 1, got 0");
  std::vector<std::vector<FloatImage>> renders(size_t(1) << n);
  for (uint32_t mask = 0; mask < renders.size(); ++mask)
    for (uint32_t s = 0; s < options.seeds; ++s) renders[mask].push_back(render(mask, s));
  return attribute_renders(stages, renders, reference, rois, options);
}

}  // namespace gib::attribution
