// Error attribution's arithmetic (harness/attribution/) on inputs with known answers: exact
// Shapley values, cheap pairs, the bias^2 / variance split, and synthetic techniques whose
// stages are wrong by known amounts. No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "harness/attribution/attribution.h"
#include "harness/attribution/attribution_report.h"

namespace gib::attribution {
namespace {

TEST(Attribution, ShapleyKnownAnswer) {
  // Two stages: v(none) 10, v({0}) 4, v({1}) 6, v(both) 0.
  const std::vector<double> v = {10, 4, 6, 0};
  const std::vector<double> phi = shapley(v, 2);
  EXPECT_DOUBLE_EQ(phi[0], 0.5 * ((10 - 4) + (6 - 0)));
  EXPECT_DOUBLE_EQ(phi[1], 0.5 * ((10 - 6) + (4 - 0)));
  const CheapPair p0 = cheap_pair(v, 2, 0);
  EXPECT_DOUBLE_EQ(p0.alone, 6);  // v(none) - v({0})
  EXPECT_DOUBLE_EQ(p0.last, 6);   // v({1}) - v(both)
  const CheapPair p1 = cheap_pair(v, 2, 1);
  EXPECT_DOUBLE_EQ(p1.alone, 4);
  EXPECT_DOUBLE_EQ(p1.last, 4);
}

TEST(Attribution, ShapleyValuesSumToTheGapExactly) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 100.0);
  for (uint32_t n = 1; n <= kMaxStages; ++n) {
    std::vector<double> v(size_t(1) << n);
    for (double& x : v) x = u(rng);
    const std::vector<double> phi = shapley(v, n);
    const double sum = std::accumulate(phi.begin(), phi.end(), 0.0);
    EXPECT_NEAR(sum, v.front() - v.back(), 1e-12 * 100.0 * (1u << n)) << n << " stages";
  }
  // A game where stage 2 is a dummy (its oracle never changes anything) gives it exactly 0.
  std::vector<double> v(8);
  for (uint32_t s = 0; s < 8; ++s) v[s] = 10.0 - 3.0 * (s & 1) - 5.0 * ((s >> 1) & 1) + ((s & 3) == 3 ? 1.0 : 0.0);
  EXPECT_DOUBLE_EQ(shapley(v, 3)[2], 0.0);
}

TEST(Attribution, BadGamesAreOneClearError) {
  EXPECT_THROW(shapley({1.0}, 0), std::invalid_argument);
  EXPECT_THROW(shapley(std::vector<double>(128), 7), std::invalid_argument);
  try {
    shapley({1, 2, 3}, 2);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "attribution: expected 2^2 = 4 subset values, got 3");
  }
}

TEST(Attribution, BiasVarianceSplitKnownAnswer) {
  // Reference 1 everywhere; seeds 1 and 3: per seed MSE 0 and 4, mean 2 = bias^2 1 + variance 1.
  FloatImage ref(4, 2, 4, 1.0f), a(4, 2, 4, 1.0f), b(4, 2, 4, 3.0f);
  const RoiError e = roi_error({a, b}, ref, metrics::roi_pixels({}, 4, 2));
  EXPECT_DOUBLE_EQ(e.mse, 2.0);
  EXPECT_DOUBLE_EQ(e.bias2, 1.0);
  EXPECT_DOUBLE_EQ(e.variance, 1.0);
  EXPECT_NEAR(e.signed_energy, 1.0, 1e-12);  // the mean image holds twice the energy
  EXPECT_NEAR(e.abs_energy, 1.0, 1e-12);
  // Half the pixels too bright, half too dark by as much: the signed ratio cancels, the absolute does not.
  FloatImage c(4, 2, 4, 1.0f);
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t ch = 0; ch < 3; ++ch) {
      c.at(x, 0, ch) = 1.5f;
      c.at(x, 1, ch) = 0.5f;
    }
  const RoiError f = roi_error({c}, ref, metrics::roi_pixels({}, 4, 2));
  EXPECT_NEAR(f.signed_energy, 0.0, 1e-12);
  EXPECT_NEAR(f.abs_energy, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(f.variance, 0.0);
  EXPECT_THROW(roi_error({FloatImage(3, 2, 4)}, ref, metrics::roi_pixels({}, 4, 2)), std::invalid_argument);
}

// A synthetic three-stage technique over a smooth truth image: "probes" (exact: outputs the
// truth), "gather" (scales its input by `gather_scale`), "denoise" (adds per-seed noise of
// `noise`; its oracle, the mean of many renders of its input, is the input). The reference is
// the truth plus its own fixed noise.
struct Synthetic {
  static constexpr uint32_t kW = 64, kH = 32;
  float gather_scale = 0.8f, noise = 0.01f, reference_noise = 0.002f;
  FloatImage truth{kW, kH, 4};
  FloatImage reference{kW, kH, 4};
  Synthetic() {
    std::mt19937 rng(11);
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x)
        for (uint32_t c = 0; c < 4; ++c) {
          truth.at(x, y, c) = 0.5f + 0.3f * std::sin(0.2f * float(x) + 0.1f * float(c)) * std::cos(0.3f * float(y));
          reference.at(x, y, c) = truth.at(x, y, c) + reference_noise * n(rng);
        }
  }
  FloatImage render(uint32_t mask, uint32_t seed) const {
    std::mt19937 rng(1000 + seed);
    std::normal_distribution<float> n(0.0f, 1.0f);
    FloatImage out(kW, kH, 4);
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x)
        for (uint32_t c = 0; c < 4; ++c) {
          float v = truth.at(x, y, c);                 // probes: exact with or without its oracle
          if (!(mask & 2u)) v *= gather_scale;          // gather's defect; its oracle passes v on
          if (!(mask & 4u)) v += noise * n(rng);        // denoise's residual noise
          out.at(x, y, c) = v;
        }
    return out;
  }
  double noise_floor() const { return double(reference_noise) * reference_noise; }
  Attribution run(uint32_t seeds = 4) const {
    Options o;
    o.seeds = seeds;
    o.noise_floor = {noise_floor(), noise_floor()};
    return attribute({"probes", "gather", "denoise"}, [&](uint32_t m, uint32_t s) { return render(m, s); }, reference,
                     {{"all", {}}, {"left", {0.0, 0.0, 0.5, 1.0}}}, o);
  }
};

TEST(Attribution, AWrongGatherTakesAtLeast90PercentOfTheGap) {
  const Attribution a = Synthetic().run();
  ASSERT_EQ(a.renders, 8u * 4u);
  for (const RoiAttribution& r : a.rois) {
    const double gap = r.none.mse - r.all.mse;
    ASSERT_GT(gap, 0.0);
    EXPECT_GE(r.stages[1].shapley, 0.9 * gap) << r.roi;
    EXPECT_EQ(r.largest, 1) << r.roi;
    // The gather's defect is a bias: what its oracle removes is bias^2, not variance.
    EXPECT_NEAR(r.stages[1].bias_removed, r.stages[1].shapley, 0.02 * gap);
    // It darkens by 20%: its share of the signed energy ratio is about -0.2.
    EXPECT_NEAR(r.stages[1].signed_energy, -0.2, 0.01);
    double sum = 0;
    for (const StageBar& b : r.stages) sum += b.shapley;
    EXPECT_NEAR(sum, gap, 1e-12);
  }
}

TEST(Attribution, TheDenoisersOracleRemovesVariance) {
  Synthetic s;
  s.gather_scale = 1.0f;
  s.noise = 0.05f;
  const Attribution a = s.run();
  const StageBar& d = a.rois[0].stages[2];
  EXPECT_EQ(a.rois[0].largest, 2);
  // Variance over 4 seeds (1/K) is 3/4 of the noise's 0.0025.
  EXPECT_NEAR(d.variance_removed, 0.75 * 0.0025, 0.2 * 0.0025);
  EXPECT_GT(d.variance_removed, d.bias_removed);
  EXPECT_NEAR(d.shapley, d.bias_removed + d.variance_removed, 1e-12);
}

TEST(Attribution, EveryOracleInPlaceIsTheOracleFloor) {
  const Synthetic s;
  const Attribution a = s.run();
  // With every stage an oracle the chain outputs the truth: the error left is the reference's own noise.
  const RoiError floor = roi_error({s.truth}, s.reference, metrics::roi_pixels({}, Synthetic::kW, Synthetic::kH));
  EXPECT_DOUBLE_EQ(a.rois[0].all.mse, floor.mse);
  EXPECT_NEAR(a.rois[0].all.mse, s.noise_floor(), 0.1 * s.noise_floor());
  EXPECT_FALSE(a.rois[0].floor_disagrees);
  // An oracle that disagrees with the reference (a 5% bias left in every oracle) is flagged.
  Options o;
  o.seeds = 1;
  o.noise_floor = {s.noise_floor()};
  const Attribution biased = attribute(
      {"gather"},
      [&](uint32_t m, uint32_t seed) {
        FloatImage img = s.render(m ? 6u : 4u, seed);
        if (m)
          for (float& v : img.pixels) v *= 1.05f;
        return img;
      },
      s.reference, {{"all", {}}}, o);
  EXPECT_TRUE(biased.rois[0].floor_disagrees);
}

TEST(Attribution, AnExactStageGetsAboutNothing) {
  const Attribution a = Synthetic().run();
  for (const RoiAttribution& r : a.rois) {
    EXPECT_LT(std::abs(r.stages[0].shapley), 3.0 * r.noise_floor) << r.roi;
    EXPECT_FALSE(r.stages[0].resolved) << r.roi;  // reported as "not resolved", never ranked
    EXPECT_TRUE(r.stages[1].resolved) << r.roi;
  }
}

// FLIP as its own game: v(S) = the ROI's mean per-pixel error over the seeds, exact Shapley
// values summing to its own gap, reported beside (never inside) the MSE bars. Here the per-pixel
// error is |render - reference| in channel 0, so the known answer is the mean absolute error.
TEST(Attribution, FlipIsItsOwnGame) {
  const Synthetic s;
  Options o;
  o.seeds = 2;
  o.noise_floor = {s.noise_floor()};
  o.flip_map = [&](const FloatImage& img) {
    FloatImage e(img.width, img.height, 1);
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) e.at(x, y, 0) = std::abs(img.at(x, y, 0) - s.reference.at(x, y, 0));
    return e;
  };
  const Attribution a = attribute({"probes", "gather", "denoise"}, [&](uint32_t m, uint32_t seed) { return s.render(m, seed); },
                                  s.reference, {{"all", {}}}, o);
  const RoiAttribution& r = a.rois[0];
  ASSERT_EQ(r.flip.size(), 8u);
  ASSERT_EQ(r.flip_shapley.size(), 3u);
  EXPECT_NEAR(r.flip_shapley[0] + r.flip_shapley[1] + r.flip_shapley[2], r.flip[0] - r.flip[7], 1e-12);
  double mae = 0;  // v(none) by hand: seeds 0 and 1 of the untouched chain
  for (uint32_t seed = 0; seed < 2; ++seed) {
    const FloatImage img = s.render(0, seed);
    for (uint32_t y = 0; y < Synthetic::kH; ++y)
      for (uint32_t x = 0; x < Synthetic::kW; ++x)
        mae += std::abs(double(img.at(x, y, 0)) - s.reference.at(x, y, 0)) / (2.0 * Synthetic::kW * Synthetic::kH);
  }
  EXPECT_NEAR(r.flip[0], mae, 1e-6);
  EXPECT_GT(r.flip_shapley[1], 0.5 * (r.flip[0] - r.flip[7]));  // the scaled gather holds most of it
  EXPECT_NEAR(r.flip_shapley[0], 0.0, 1e-9);                    // the exact probes stage changes nothing
  ReportContext ctx{"synthetic", "chain", "medium", "radiance", "cpu", {{"probes", {"p"}, "exact"}}};
  EXPECT_NE(format_table(a, ctx).find("FLIP game (its own: FLIP is not additive per pixel)"), std::string::npos);
  const nlohmann::json j = to_json(a, ctx);
  EXPECT_NEAR(j["rois"][0]["flip_game"]["technique"].get<double>(), r.flip[0], 1e-12);
  EXPECT_NE(waterfall_html(a, ctx).find("FLIP game"), std::string::npos);
  // Without a flip_map there is no FLIP game and nothing about it in the outputs.
  EXPECT_TRUE(s.run().rois[0].flip.empty());
}

TEST(Attribution, TableJsonAndWaterfallSayTheSame) {
  const Attribution a = Synthetic().run(2);
  ReportContext ctx{"synthetic", "chain", "medium", "radiance", "cpu",
                    {{"probes", {"p"}, "exact"}, {"trace", {"t"}, ""}, {"gather", {"g"}, "x"}, {"denoise", {"d"}, "y"}}};
  const std::string table = format_table(a, ctx);
  EXPECT_NE(table.find("trace        no oracle yet (t)"), std::string::npos) << table;
  EXPECT_NE(table.find("not resolved"), std::string::npos);           // the exact probes stage
  EXPECT_NE(table.find("largest share: gather"), std::string::npos);
  const nlohmann::json j = to_json(a, ctx);
  ASSERT_EQ(j["rois"].size(), 2u);
  double sum = 0;
  for (const auto& b : j["rois"][0]["bars"]) sum += b["shapley"].get<double>();
  EXPECT_NEAR(sum, j["rois"][0]["technique"]["mse"].get<double>() - j["rois"][0]["oracle_floor"]["mse"].get<double>(),
              1e-12);
  EXPECT_EQ(j["rois"][0]["subsets"].size(), 8u);
  EXPECT_EQ(j["rois"][0]["largest"], "gather");
  const std::string html = waterfall_html(a, ctx);
  size_t svgs = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++svgs;
  EXPECT_EQ(svgs, 2u);  // one waterfall per ROI
  EXPECT_EQ(mask_names(a.stages, 5), "probes, denoise");
  EXPECT_EQ(mask_names(a.stages, 0), "none");
}

}  // namespace
}  // namespace gib::attribution
