// Error attribution: which stage of a technique loses the accuracy. The stages with an oracle
// play a game whose value v(S) is the final error (per ROI, averaged over seeds) with the
// stages in S replaced by their oracles; each stage's bar is its exact Shapley value of
// v(none) - v(all), split into the bias^2 and the variance it removes, with a confidence
// interval from the per-seed games; the all-oracles error is the oracle floor, its own bar.
// `render` does the rendering (the gibench command: a case's technique with graph overrides;
// the tests: synthetic techniques), so this file is arithmetic over renders.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/attribution/game.h"
#include "harness/attribution/roi_error.h"

namespace gib::attribution {

// The compared image of one render with the stages of `oracle_mask` (bit i = stage i) replaced
// by their oracles, at seed index `seed` (0..seeds-1).
using RenderFn = std::function<FloatImage(uint32_t oracle_mask, uint32_t seed)>;

struct NamedRoi {
  std::string name;
  metrics::Roi box;
};

struct Options {
  uint32_t seeds = 2;
  // Per ROI (the `rois` order), the reference's own noise in MSE units (its per-pixel variance
  // against the converged value); 0 when unknown. Differences below 3x it are "not resolved".
  std::vector<double> noise_floor;
  // The per-pixel FLIP error of a render against the reference (1 channel, [0, 1]); empty: no
  // FLIP game. FLIP is not additive over pixels or stages, so it is its own game (v(S) = the
  // ROI's mean FLIP over the seeds), reported beside the MSE bars, never summed with them.
  std::function<FloatImage(const FloatImage& render)> flip_map;
};

struct StageBar {
  std::string stage;
  double shapley = 0;             // of the MSE gap; the bars sum to v(none) - v(all)
  double bias_removed = 0;        // Shapley of the bias^2 game (bias_removed + variance_removed = shapley)
  double variance_removed = 0;    // Shapley of the variance game
  double ci95 = 0;                // half-width over the per-seed games (0 with one seed)
  double signed_energy = 0;       // its Shapley share of the signed energy ratio (negative: it darkens)
  CheapPair pair;                 // alone / last
  bool resolved = true;           // |shapley| >= 3x the noise floor
};

struct RoiAttribution {
  std::string roi;
  RoiError none, all;             // the technique as is; every oracle in place (the oracle floor)
  std::vector<RoiError> subsets;  // every v(S), S by bit mask
  std::vector<StageBar> stages;   // the game's stages, in declaration order
  double noise_floor = 0;
  bool floor_disagrees = false;   // the oracle floor sits above 3x the noise floor (oracle vs reference)
  int largest = -1;               // the stage with the largest share, -1 when not resolved from the next
  std::vector<double> flip;          // the FLIP game's v(S) by bit mask (empty: no FLIP game)
  std::vector<double> flip_shapley;  // its Shapley values, in stage order
};

struct Attribution {
  std::vector<std::string> stages;
  uint32_t seeds = 0, renders = 0;
  bool exact = true;  // every subset rendered (not sampled)
  std::vector<RoiAttribution> rois;
};

// Renders the 2^n subsets x seeds and plays the games; n = stages.size() in 1..kMaxStages.
Attribution attribute(const std::vector<std::string>& stages, const RenderFn& render, const FloatImage& reference,
                      const std::vector<NamedRoi>& rois, const Options& options);

// Plays the games on renders already made: renders[mask][seed].
Attribution attribute_renders(const std::vector<std::string>& stages,
                              const std::vector<std::vector<FloatImage>>& renders, const FloatImage& reference,
                              const std::vector<NamedRoi>& rois, const Options& options);

// Lag attribution: a case whose scene changes is evaluated at several frames of one run
// (Case::eval_frames), each against the reference of the scene frozen at that frame. The game is
// played at every frame, and on the integrated error: v(S) = the mean over the frames of v_f(S)
// (every error, bias^2 / variance split, energy, per-seed MSE and FLIP). The mean, not the sum:
// it keeps one frame's MSE units, so its noise floor (the frames' mean) and its waterfall read
// like a single frame's, and the shares are those of the sum. Shapley values are linear in v, so
// each integrated bar is the mean of the stage's per-frame bars and the bars sum to the mean gap.
struct LagAttribution {
  std::vector<uint32_t> frames;          // 1-based, increasing
  std::vector<Attribution> per_frame;    // one per frame
  Attribution integrated;
};

// One image per evaluation frame (in `frames` order) of one render: every frame from one run.
using FramesRenderFn = std::function<std::vector<FloatImage>(uint32_t oracle_mask, uint32_t seed)>;

// `references` and `options` (noise floor, FLIP map against that frame's reference) one per
// frame; the seeds are options.front().seeds.
LagAttribution attribute_frames(const std::vector<std::string>& stages, const FramesRenderFn& render,
                                const std::vector<uint32_t>& frames, const std::vector<FloatImage>& references,
                                const std::vector<NamedRoi>& rois, const std::vector<Options>& options);

// The integrated game of per-frame attributions of one set of stages, ROIs and seeds.
Attribution integrate(const std::vector<Attribution>& per_frame);

}  // namespace gib::attribution
