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

// The mean of channel 0 over `rect`.
double rect_mean(const FloatImage& img, const metrics::PixelRect& rect) {
  double sum = 0;
  for (uint32_t y = rect.y_begin; y < rect.y_end; ++y)
    for (uint32_t x = rect.x_begin; x < rect.x_end; ++x) sum += img.at(x, y, 0);
  return sum / double(rect.pixel_count());
}

// The stage with the largest share when it beats the next by 3x the noise floor; else -1.
int largest_resolved(const std::vector<StageBar>& bars, double noise_floor) {
  if (bars.empty()) return -1;
  std::vector<size_t> order(bars.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bars[a].shapley > bars[b].shapley; });
  if (!bars[order[0]].resolved) return -1;
  if (order.size() > 1 && bars[order[0]].shapley - bars[order[1]].shapley < 3.0 * noise_floor) return -1;
  return int(order[0]);
}

// The games of one ROI from its subsets' errors (and FLIP values, noise floor) already in `ra`.
void play(RoiAttribution& ra, const std::vector<std::string>& stages, uint32_t seeds) {
  const uint32_t n = uint32_t(stages.size());
  ra.none = ra.subsets.front();
  ra.all = ra.subsets.back();
  const std::vector<double> mse = shapley(game_of(ra.subsets, &RoiError::mse), n);
  const std::vector<double> bias = shapley(game_of(ra.subsets, &RoiError::bias2), n);
  const std::vector<double> var = shapley(game_of(ra.subsets, &RoiError::variance), n);
  const std::vector<double> energy = shapley(game_of(ra.subsets, &RoiError::signed_energy), n);
  // Per-seed games (Shapley is linear in v: their mean is the bar) give the interval.
  std::vector<std::vector<double>> per_seed;
  for (uint32_t s = 0; s < seeds; ++s) {
    std::vector<double> v;
    for (const RoiError& e : ra.subsets) v.push_back(e.per_seed_mse[s]);
    per_seed.push_back(shapley(v, n));
  }
  ra.stages.clear();
  for (uint32_t i = 0; i < n; ++i) {
    StageBar b;
    b.stage = stages[i];
    b.shapley = mse[i];
    b.bias_removed = bias[i];
    b.variance_removed = var[i];
    b.signed_energy = energy[i];  // v(S) - v(S + i): the stage's own share of the signed ratio
    b.pair = cheap_pair(game_of(ra.subsets, &RoiError::mse), n, i);
    if (seeds > 1) {
      double mean = 0, sq = 0;
      for (auto& p : per_seed) mean += p[i] / seeds;
      for (auto& p : per_seed) sq += (p[i] - mean) * (p[i] - mean);
      b.ci95 = 1.96 * std::sqrt(sq / (seeds - 1) / seeds);
    }
    // An exact 0 (nothing to remove: a frame with no error) is not resolved either.
    b.resolved = b.shapley != 0.0 && std::abs(b.shapley) >= 3.0 * ra.noise_floor;
    ra.stages.push_back(b);
  }
  ra.flip_shapley = ra.flip.empty() ? std::vector<double>{} : shapley(ra.flip, n);
  ra.floor_disagrees = ra.noise_floor > 0 && ra.all.mse > 3.0 * ra.noise_floor;
  ra.largest = largest_resolved(ra.stages, ra.noise_floor);
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
    for (const auto& maps : flip_maps) {
      double sum = 0;
      for (const FloatImage& m : maps) sum += rect_mean(m, rect) / double(maps.size());
      ra.flip.push_back(sum);
    }
    play(ra, stages, out.seeds);
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

namespace {

// The frames' mean of one subset's error (per_seed_mse element-wise).
RoiError mean_error(const std::vector<const RoiError*>& frames) {
  RoiError m;
  m.per_seed_mse.assign(frames.front()->per_seed_mse.size(), 0.0);
  const double k = double(frames.size());
  for (const RoiError* e : frames) {
    m.mse += e->mse / k;
    m.bias2 += e->bias2 / k;
    m.variance += e->variance / k;
    m.signed_energy += e->signed_energy / k;
    m.abs_energy += e->abs_energy / k;
    for (size_t s = 0; s < m.per_seed_mse.size(); ++s) m.per_seed_mse[s] += e->per_seed_mse[s] / k;
  }
  return m;
}

}  // namespace

Attribution integrate(const std::vector<Attribution>& per_frame) {
  if (per_frame.empty()) throw std::invalid_argument("attribution: expected at least one frame to integrate, got none");
  const Attribution& first = per_frame.front();
  Attribution out;
  out.stages = first.stages;
  out.seeds = first.seeds;
  out.exact = first.exact;
  for (const Attribution& f : per_frame) {
    if (f.stages != first.stages || f.seeds != first.seeds || f.rois.size() != first.rois.size())
      throw std::invalid_argument("attribution: expected the frames' games over the same stages, seeds and ROIs");
    out.renders = std::max(out.renders, f.renders);  // every frame from the same renders
  }
  const double k = double(per_frame.size());
  for (size_t r = 0; r < first.rois.size(); ++r) {
    RoiAttribution ra;
    ra.roi = first.rois[r].roi;
    // The FLIP game integrates only when every frame has one (FLIP is undefined against a
    // reference with no light, e.g. a sealed room before its wall goes).
    bool flip = true;
    for (const Attribution& f : per_frame) flip &= !f.rois[r].flip.empty();
    for (size_t m = 0; m < first.rois[r].subsets.size(); ++m) {
      std::vector<const RoiError*> errors;
      double flip_mean = 0;
      for (const Attribution& f : per_frame) {
        errors.push_back(&f.rois[r].subsets[m]);
        if (flip) flip_mean += f.rois[r].flip.at(m) / k;
      }
      ra.subsets.push_back(mean_error(errors));
      if (flip) ra.flip.push_back(flip_mean);
    }
    for (const Attribution& f : per_frame) ra.noise_floor += f.rois[r].noise_floor / k;
    play(ra, out.stages, out.seeds);
    out.rois.push_back(std::move(ra));
  }
  return out;
}

LagAttribution attribute_frames(const std::vector<std::string>& stages, const FramesRenderFn& render,
                                const std::vector<uint32_t>& frames, const std::vector<FloatImage>& references,
                                const std::vector<NamedRoi>& rois, const std::vector<Options>& options) {
  const uint32_t n = uint32_t(stages.size());
  if (n == 0 || n > kMaxStages)
    throw std::invalid_argument(fmt::format("attribution: expected 1..{} stages with an oracle, got {}", kMaxStages, n));
  if (frames.empty() || references.size() != frames.size() || options.size() != frames.size())
    throw std::invalid_argument(fmt::format("attribution: expected a reference and options per frame ({} frames), got "
                                            "{} and {}", frames.size(), references.size(), options.size()));
  const uint32_t seeds = options.front().seeds;
  if (seeds == 0) throw std::invalid_argument("attribution: expected --seeds >= 1, got 0");
  // by_frame[f][mask][seed]: each render's frames, split so every frame plays its own game.
  std::vector<std::vector<std::vector<FloatImage>>> by_frame(frames.size(),
                                                             std::vector<std::vector<FloatImage>>(size_t(1) << n));
  for (uint32_t mask = 0; mask < (1u << n); ++mask)
    for (uint32_t s = 0; s < seeds; ++s) {
      std::vector<FloatImage> images = render(mask, s);
      if (images.size() != frames.size())
        throw std::invalid_argument(fmt::format("attribution: expected a render's {} frames, got {}", frames.size(),
                                                images.size()));
      for (size_t f = 0; f < frames.size(); ++f) by_frame[f][mask].push_back(std::move(images[f]));
    }
  LagAttribution out;
  out.frames = frames;
  for (size_t f = 0; f < frames.size(); ++f)
    out.per_frame.push_back(attribute_renders(stages, by_frame[f], references[f], rois, options[f]));
  out.integrated = integrate(out.per_frame);
  return out;
}

}  // namespace gib::attribution
