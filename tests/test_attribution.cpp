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

// A synthetic chain over a scene that changes (lag attribution): the light holds for 60 frames,
// then falls linearly to a quarter by frame 121. "probes" is exact; "history" is a temporal
// filter h_f = 0.9 h_(f-1) + 0.1 s_f whose oracle is its converged history (s_f itself);
// "denoise" adds per-seed noise. Each evaluation frame's reference is the frozen scene there plus
// its own fixed noise. A render returns the frames 61, 91 and 121 of one run.
struct LagChain {
  static constexpr uint32_t kW = 48, kH = 24;
  std::vector<uint32_t> frames{61, 91, 121};
  float noise = 0.01f, reference_noise = 0.002f;
  FloatImage base{kW, kH, 4};
  std::vector<FloatImage> references;
  static double light(uint32_t f) { return f <= 60 ? 1.0 : 1.0 - 0.75 * double(f - 60) / 61.0; }
  static double lagged(uint32_t f) {  // the filter's state after frame f, from a converged start
    double h = light(1);
    for (uint32_t k = 2; k <= f; ++k) h = 0.9 * h + 0.1 * light(k);
    return h;
  }
  LagChain() {
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x)
        for (uint32_t c = 0; c < 4; ++c) base.at(x, y, c) = 0.5f + 0.3f * std::sin(0.25f * float(x + 2 * y + c));
    std::mt19937 rng(5);
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (uint32_t f : frames) {
      FloatImage ref = base;
      for (float& v : ref.pixels) v = v * float(light(f)) + reference_noise * n(rng);
      references.push_back(ref);
    }
  }
  std::vector<FloatImage> render(uint32_t mask, uint32_t seed) const {
    std::mt19937 rng(2000 + seed);
    std::normal_distribution<float> n(0.0f, 1.0f);
    std::vector<FloatImage> out;
    for (uint32_t f : frames) {
      const float scale = float(mask & 2u ? light(f) : lagged(f));  // history's oracle: converged
      FloatImage img = base;
      for (float& v : img.pixels) v = v * scale + (mask & 4u ? 0.0f : noise * n(rng));
      out.push_back(img);
    }
    return out;
  }
  LagAttribution run(uint32_t seeds = 3) const {
    std::vector<Options> o(frames.size());
    for (Options& x : o) {
      x.seeds = seeds;
      x.noise_floor = {double(reference_noise) * reference_noise, double(reference_noise) * reference_noise};
    }
    return attribute_frames({"probes", "history", "denoise"}, [&](uint32_t m, uint32_t s) { return render(m, s); },
                            frames, references, {{"all", {}}, {"top", {0.0, 0.0, 1.0, 0.5}}}, o);
  }
};

TEST(Attribution, ALaggingStageTakesAtLeast90PercentOfTheIntegratedGap) {
  const LagAttribution a = LagChain().run();
  ASSERT_EQ(a.per_frame.size(), 3u);
  EXPECT_EQ(a.integrated.renders, 8u * 3u);  // one run per subset and seed gives every frame
  for (size_t r = 0; r < a.integrated.rois.size(); ++r) {
    const RoiAttribution& x = a.integrated.rois[r];
    const double gap = x.none.mse - x.all.mse;
    ASSERT_GT(gap, 0.0);
    EXPECT_GE(x.stages[1].shapley, 0.9 * gap) << x.roi;
    EXPECT_EQ(x.largest, 1) << x.roi;
    // The lag keeps the old, brighter light: its share of the signed energy ratio is positive.
    EXPECT_GT(x.stages[1].signed_energy, 0.0) << x.roi;
    // The integrated game is the mean of the frames' games: its error and each bar the frames' mean.
    double mean_error = 0, mean_bar = 0;
    for (const Attribution& f : a.per_frame) {
      mean_error += f.rois[r].none.mse / 3.0;
      mean_bar += f.rois[r].stages[1].shapley / 3.0;
    }
    EXPECT_NEAR(x.none.mse, mean_error, 1e-15);
    EXPECT_NEAR(x.stages[1].shapley, mean_bar, 1e-15);
  }
  // The lag grows as the light falls: the history's bar at frame 121 is well above frame 61's.
  EXPECT_GT(a.per_frame[2].rois[0].stages[1].shapley, 10.0 * a.per_frame[0].rois[0].stages[1].shapley);
}

TEST(Attribution, LagBarsSumToTheirGapsExactly) {
  const LagAttribution a = LagChain().run();
  auto check = [](const Attribution& g, const std::string& what) {
    for (const RoiAttribution& x : g.rois) {
      double sum = 0;
      for (const StageBar& b : x.stages) sum += b.shapley;
      EXPECT_NEAR(sum, x.none.mse - x.all.mse, 1e-12 * x.none.mse) << what << " " << x.roi;
    }
  };
  check(a.integrated, "integrated");
  for (size_t f = 0; f < a.frames.size(); ++f) check(a.per_frame[f], "frame " + std::to_string(a.frames[f]));
}

TEST(Attribution, AnExactStageIsNotResolvedOverTime) {
  const LagAttribution a = LagChain().run();
  for (const RoiAttribution& x : a.integrated.rois) {
    EXPECT_FALSE(x.stages[0].resolved) << x.roi;
    EXPECT_LT(std::abs(x.stages[0].shapley), 3.0 * x.noise_floor) << x.roi;
  }
  for (const Attribution& f : a.per_frame) EXPECT_FALSE(f.rois[0].stages[0].resolved);
}

TEST(Attribution, LagInputsAreOneClearError) {
  const LagChain c;
  std::vector<Options> o(2);
  EXPECT_THROW(attribute_frames({"probes"}, [&](uint32_t m, uint32_t s) { return c.render(m, s); }, c.frames,
                                c.references, {{"all", {}}}, o),
               std::invalid_argument);  // options for 2 of 3 frames
  o.resize(3);
  try {
    attribute_frames({"probes"}, [&](uint32_t, uint32_t) { return std::vector<FloatImage>(2, c.base); }, c.frames,
                     c.references, {{"all", {}}}, o);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "attribution: expected a render's 3 frames, got 2");
  }
  EXPECT_THROW(integrate({}), std::invalid_argument);
}

TEST(Attribution, FlipIntegratesOnlyWhenEveryFrameHasIt) {
  const LagChain c;
  std::vector<Options> o(3);
  for (size_t f = 1; f < 3; ++f)  // frame 61 plays no FLIP game (as against a reference with no light)
    o[f].flip_map = [](const FloatImage& img) { return FloatImage(img.width, img.height, 1, 0.5f); };
  const LagAttribution a = attribute_frames({"probes", "history"}, [&](uint32_t m, uint32_t s) { return c.render(m, s); },
                                            c.frames, c.references, {{"all", {}}}, o);
  EXPECT_TRUE(a.per_frame[0].rois[0].flip.empty());
  EXPECT_EQ(a.per_frame[1].rois[0].flip.size(), 4u);
  EXPECT_TRUE(a.integrated.rois[0].flip.empty());
}

TEST(Attribution, AFrameWithNoErrorRanksNoStage) {
  // A sealed room before its wall goes: reference and render are 0, the noise floor too.
  const FloatImage black(8, 4, 4, 0.0f);
  Options o;
  o.seeds = 1;
  o.noise_floor = {0.0};
  const Attribution a = attribute({"probes", "history"}, [&](uint32_t, uint32_t) { return black; }, black,
                                  {{"all", {}}}, o);
  EXPECT_EQ(a.rois[0].largest, -1);
  EXPECT_FALSE(a.rois[0].stages[0].resolved);
}

TEST(Attribution, LagTableJsonAndPageSayTheSame) {
  const LagAttribution a = LagChain().run(2);
  ReportContext ctx{"lag", "chain", "medium", "indirect_diffuse", "cpu",
                    {{"probes", {"p"}, "exact"}, {"history", {"h"}, "converged"}, {"denoise", {"d"}, "mean"}}};
  const std::string table = format_table(a, ctx);
  EXPECT_NE(table.find("frames 61, 91, 121"), std::string::npos) << table;
  EXPECT_NE(table.find("INTEGRATED"), std::string::npos);
  EXPECT_NE(table.find("PER FRAME"), std::string::npos);
  EXPECT_NE(table.find("largest share: history"), std::string::npos) << table;
  const nlohmann::json j = to_json(a, ctx);
  EXPECT_EQ(j["rois"][0]["largest"], "history");
  EXPECT_NEAR(j["rois"][0]["technique"]["mse"].get<double>(), a.integrated.rois[0].none.mse, 1e-15);
  ASSERT_EQ(j["lag"]["per_frame"].size(), 3u);
  EXPECT_EQ(j["lag"]["per_frame"][2]["frame"], 121);
  EXPECT_NEAR(j["lag"]["per_frame"][2]["rois"][0]["bars"][1]["shapley"].get<double>(),
              a.per_frame[2].rois[0].stages[1].shapley, 1e-15);
  const std::string html = waterfall_html(a, ctx);
  size_t svgs = 0, tables = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++svgs;
  for (size_t at = html.find("<table"); at != std::string::npos; at = html.find("<table", at + 1)) ++tables;
  EXPECT_EQ(svgs, 2u);    // one integrated waterfall per ROI
  EXPECT_EQ(tables, 2u);  // one per-frame table per ROI
}

}  // namespace
}  // namespace gib::attribution
