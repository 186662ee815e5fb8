// Image metrics with known answers: every expected value is derived by hand in a comment.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "metrics/image_metrics.h"

namespace gib::metrics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kInff = std::numeric_limits<float>::infinity();

// Inverse of the sRGB OETF, written independently of the library so the PSNR tests can place
// values at exact display codes.
double srgb_to_linear(double s) {
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

FloatImage solid(uint32_t w, uint32_t h, float r, float g, float b) {
  FloatImage img(w, h, 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      img.at(x, y, 0) = r;
      img.at(x, y, 1) = g;
      img.at(x, y, 2) = b;
    }
  return img;
}

FloatImage grey(uint32_t w, uint32_t h, float v) { return FloatImage(w, h, 1, v); }

// Horizontal ramp over `w` pixels, values (x + 0.5) / w, optionally quantised to `levels` levels
// (floor(v * levels) / levels). With w and levels powers of two every value is exact in float.
FloatImage ramp(uint32_t w, uint32_t h, uint32_t levels = 0) {
  FloatImage img(w, h, 1);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      double v = (x + 0.5) / w;
      if (levels) v = std::floor(v * levels) / levels;
      img.at(x, y, 0) = float(v);
    }
  return img;
}

FloatImage transpose(const FloatImage& img) {
  FloatImage out(img.height, img.width, img.channels);
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x)
      for (uint32_t c = 0; c < img.channels; ++c) out.at(y, x, c) = img.at(x, y, c);
  return out;
}

// ---- tone map and PSNR

TEST(MetricsTonemap, SrgbOetfKnownPoints) {
  EXPECT_DOUBLE_EQ(srgb_oetf(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_oetf(1.0), 1.0);
  EXPECT_NEAR(srgb_oetf(0.0031308), 0.0031308 * 12.92, 1e-12);  // the linear segment's end
  EXPECT_NEAR(srgb_oetf(srgb_to_linear(0.5)), 0.5, 1e-12);
  EXPECT_NEAR(srgb_oetf(0.18), 0.4613561, 1e-6);  // 1.055 * 0.18^(1/2.4) - 0.055
}

TEST(MetricsTonemap, ClampsKeepsAlphaAndShape) {
  FloatImage img(2, 1, 4);
  img.pixels = {-1.0f, 0.5f, 7.0f, 0.25f, kNaNf, 1.0f, 0.0f, 3.0f};
  const FloatImage t = tonemap_srgb(img);
  ASSERT_EQ(t.width, 2u);
  ASSERT_EQ(t.height, 1u);
  ASSERT_EQ(t.channels, 4u);
  EXPECT_FLOAT_EQ(t.pixels[0], 0.0f);                       // negative clamps to black
  EXPECT_NEAR(t.pixels[1], srgb_oetf(0.5), 1e-6);
  EXPECT_FLOAT_EQ(t.pixels[2], 1.0f);                       // over 1 clips to white
  EXPECT_FLOAT_EQ(t.pixels[3], 0.25f);                      // alpha untouched
  EXPECT_TRUE(std::isnan(t.pixels[4]));                     // NaN is not hidden
  EXPECT_FLOAT_EQ(t.pixels[7], 3.0f);
}

TEST(MetricsTonemap, GreyAlphaOnlyMapsGrey) {
  FloatImage img(1, 1, 2);
  img.pixels = {4.0f, 0.5f};
  const FloatImage t = tonemap_srgb(img);
  EXPECT_FLOAT_EQ(t.pixels[0], 1.0f);
  EXPECT_FLOAT_EQ(t.pixels[1], 0.5f);
}

TEST(MetricsPsnr, ConstantSrgbOffsetGivesKnownDb) {
  // sRGB 0.5 against sRGB 0.6 everywhere: MSE = 0.1^2 = 0.01, PSNR = 10 log10(100) = 20 dB.
  const float a = float(srgb_to_linear(0.5)), b = float(srgb_to_linear(0.6));
  EXPECT_NEAR(psnr(solid(8, 8, a, a, a), solid(8, 8, b, b, b)), 20.0, 1e-4);
  // Symmetric in ref and test.
  EXPECT_NEAR(psnr(solid(8, 8, b, b, b), solid(8, 8, a, a, a)), 20.0, 1e-4);
}

TEST(MetricsPsnr, OffsetOnHalfThePixelsAndOneChannel) {
  // Half the pixels differ by 0.1 in sRGB: MSE = 0.01 / 2, PSNR = 10 log10(200) = 23.0103 dB.
  const float a = float(srgb_to_linear(0.5)), b = float(srgb_to_linear(0.6));
  FloatImage ref = solid(4, 4, a, a, a), test = ref;
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      for (uint32_t c = 0; c < 3; ++c) test.at(x, y, c) = b;
  EXPECT_NEAR(psnr(ref, test), 10.0 * std::log10(200.0), 1e-4);
  // Only the green channel differs, by 0.3 in sRGB, everywhere: MSE = 0.09 / 3 = 0.03,
  // PSNR = 10 log10(1 / 0.03) = 15.2288 dB.
  const float c = float(srgb_to_linear(0.2));
  EXPECT_NEAR(psnr(solid(4, 4, c, c, c), solid(4, 4, c, float(srgb_to_linear(0.5)), c)), 15.228787, 1e-4);
}

TEST(MetricsPsnr, IdenticalIsInfinity) {
  const FloatImage img = ramp(16, 4);
  EXPECT_EQ(psnr(img, img), kInf);
}

TEST(MetricsPsnr, ClampsBeforeComparing) {
  // Exposure 1, no tone curve: everything above 1 is white and everything below 0 is black.
  EXPECT_EQ(psnr(solid(2, 2, 1.0f, 1.0f, 1.0f), solid(2, 2, 5.0f, 2.0f, 1e6f)), kInf);
  EXPECT_EQ(psnr(grey(2, 2, 0.0f), grey(2, 2, -3.0f)), kInf);
  // White against black: MSE 1, PSNR 0 dB.
  EXPECT_NEAR(psnr(grey(2, 2, 0.0f), grey(2, 2, 10.0f)), 0.0, 1e-12);
}

TEST(MetricsPsnr, GreyEqualsReplicatedRgb) {
  const float a = float(srgb_to_linear(0.5)), b = float(srgb_to_linear(0.6));
  EXPECT_NEAR(psnr(grey(4, 4, a), grey(4, 4, b)), 20.0, 1e-4);
  EXPECT_NEAR(psnr(grey(4, 4, a), solid(4, 4, b, b, b)), 20.0, 1e-4);
}

TEST(MetricsPsnr, NaNPropagatesAndBadInputThrows) {
  FloatImage test = grey(2, 2, 0.5f);
  test.pixels[3] = kNaNf;
  EXPECT_TRUE(std::isnan(psnr(grey(2, 2, 0.5f), test)));
  EXPECT_THROW(psnr(grey(2, 2, 0.5f), grey(3, 2, 0.5f)), std::invalid_argument);
  EXPECT_THROW(psnr(FloatImage(), FloatImage()), std::invalid_argument);
  FloatImage bad(2, 2, 3);
  bad.pixels.pop_back();
  EXPECT_THROW(psnr(bad, solid(2, 2, 0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(psnr(FloatImage(2, 2, 5), FloatImage(2, 2, 5)), std::invalid_argument);
}

TEST(MetricsPsnr, DescriptionSaysWhatWasMeasured) {
  const std::string d = psnr_description();
  EXPECT_NE(d.find("sRGB"), std::string::npos);
  EXPECT_NE(d.find("exposure 1"), std::string::npos);
  EXPECT_NE(d.find("no tone curve"), std::string::npos);
  EXPECT_NE(d.find("inf"), std::string::npos);
  EXPECT_EQ(d.find('\n'), std::string::npos);
}

// ---- relative MSE

TEST(MetricsRelmse, KnownValues) {
  // (2 - 1)^2 / (1 + 0.01) = 1 / 1.01.
  EXPECT_NEAR(relmse(grey(3, 3, 1.0f), grey(3, 3, 2.0f)), 1.0 / 1.01, 1e-12);
  // On black the error is measured against eps: 0.1^2 / (0 + 0.01) = 1.
  EXPECT_NEAR(relmse(grey(3, 3, 0.0f), grey(3, 3, 0.1f)), 1.0, 1e-6);
  // eps = 1: (3 - 1)^2 / (1 + 1) = 2.
  EXPECT_NEAR(relmse(grey(3, 3, 1.0f), grey(3, 3, 3.0f), 1.0), 2.0, 1e-12);
  EXPECT_EQ(relmse(ramp(8, 2), ramp(8, 2)), 0.0);
}

TEST(MetricsRelmse, MeanOverPixelsAndChannels) {
  // One of four pixels, in one of three channels, has (2 - 1)^2 / 1.01: mean = 1 / (1.01 * 12).
  FloatImage ref = solid(2, 2, 1, 1, 1), test = ref;
  test.at(1, 1, 2) = 2.0f;
  EXPECT_NEAR(relmse(ref, test), 1.0 / (1.01 * 12.0), 1e-12);
  // HDR: a relative error of 10% on a value of 100 weighs about like one on a value of 1.
  EXPECT_NEAR(relmse(grey(1, 1, 100.0f), grey(1, 1, 110.0f)), 100.0 / (10000.0 + 0.01), 1e-9);
}

TEST(MetricsRelmse, RejectsBadEps) {
  EXPECT_THROW(relmse(grey(1, 1, 1), grey(1, 1, 1), 0.0), std::invalid_argument);
  EXPECT_THROW(relmse(grey(1, 1, 1), grey(1, 1, 1), -1.0), std::invalid_argument);
}

// ---- ROI luminance

FloatImage half_black_half_white() {
  FloatImage img = solid(8, 4, 0, 0, 0);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 4; x < 8; ++x)
      for (uint32_t c = 0; c < 3; ++c) img.at(x, y, c) = 1.0f;
  return img;
}

TEST(MetricsRoi, HalfBlackHalfWhite) {
  const FloatImage img = half_black_half_white();
  EXPECT_NEAR(roi_mean_luminance(img, 0, 0, 1, 1), 0.5, 1e-12);
  EXPECT_NEAR(roi_mean_luminance(img, 0, 0, 0.5, 1), 0.0, 1e-12);
  EXPECT_NEAR(roi_mean_luminance(img, 0.5, 0, 1, 1), 1.0, 1e-12);
  EXPECT_NEAR(roi_mean_luminance(img, 0.25, 0.5, 0.75, 1), 0.5, 1e-12);
  // Columns 3..7 (centres 3.5/8 .. 7.5/8): one black, four white.
  EXPECT_NEAR(roi_mean_luminance(img, 0.4, 0, 1, 1), 0.8, 1e-12);
}

TEST(MetricsRoi, PixelCentreRule) {
  // Width 8: pixel i's centre is (i + 0.5) / 8. [0.06, 0.07) holds centre 0.0625 only.
  const PixelRect r = roi_pixels(Roi{0.06, 0.0, 0.07, 1.0}, 8, 4);
  EXPECT_EQ(r.x_begin, 0u);
  EXPECT_EQ(r.x_end, 1u);
  EXPECT_EQ(r.y_begin, 0u);
  EXPECT_EQ(r.y_end, 4u);
  // Half-open: a box ending exactly on a centre excludes it, one starting on it includes it.
  EXPECT_THROW(roi_pixels(Roi{0.0, 0.0, 0.0625, 1.0}, 8, 4), std::invalid_argument);
  const PixelRect s = roi_pixels(Roi{0.0625, 0.0, 0.1875, 1.0}, 8, 4);
  EXPECT_EQ(s.x_begin, 0u);
  EXPECT_EQ(s.x_end, 1u);
  // Adjacent boxes partition the pixels.
  EXPECT_EQ(roi_pixels(Roi{0.0, 0.0, 0.3, 1.0}, 8, 4).x_end, roi_pixels(Roi{0.3, 0.0, 1.0, 1.0}, 8, 4).x_begin);
}

TEST(MetricsRoi, Rec709Weights) {
  EXPECT_NEAR(roi_mean_luminance(solid(2, 2, 1, 0, 0), Roi{}), 0.2126, 1e-7);
  EXPECT_NEAR(roi_mean_luminance(solid(2, 2, 0, 1, 0), Roi{}), 0.7152, 1e-7);
  EXPECT_NEAR(roi_mean_luminance(solid(2, 2, 0, 0, 1), Roi{}), 0.0722, 1e-7);
  EXPECT_NEAR(roi_mean_luminance(grey(2, 2, 0.25f), Roi{}), 0.25, 1e-12);
}

TEST(MetricsRoi, BadBoxesThrow) {
  const FloatImage img = half_black_half_white();
  EXPECT_THROW(roi_mean_luminance(img, 0.5, 0, 0.5, 1), std::invalid_argument);   // empty
  EXPECT_THROW(roi_mean_luminance(img, 0.6, 0, 0.4, 1), std::invalid_argument);   // reversed
  EXPECT_THROW(roi_mean_luminance(img, -0.1, 0, 0.5, 1), std::invalid_argument);  // outside
  EXPECT_THROW(roi_mean_luminance(img, 0, 0, 1.5, 1), std::invalid_argument);
  EXPECT_THROW(roi_mean_luminance(img, std::nan(""), 0, 1, 1), std::invalid_argument);
  EXPECT_THROW(roi_mean_luminance(img, 0.01, 0, 0.02, 1), std::invalid_argument);  // between centres
}

// ---- absolute errors

TEST(MetricsAbsError, MaxAndMean) {
  FloatImage ref(2, 2, 4, 0.0f), test = ref;
  test.at(1, 0, 0) = 0.5f;
  test.at(1, 0, 1) = -1.0f;
  test.at(1, 0, 2) = 0.25f;
  test.at(0, 1, 3) = 100.0f;  // alpha is not compared
  EXPECT_DOUBLE_EQ(max_abs_error(ref, test), 1.0);
  EXPECT_DOUBLE_EQ(mean_abs_error(ref, test), (0.5 + 1.0 + 0.25) / 12.0);
  EXPECT_EQ(max_abs_error(ref, ref), 0.0);
  EXPECT_EQ(mean_abs_error(ref, ref), 0.0);
}

TEST(MetricsAbsError, NaNIsNotLost) {
  // The NaN comes first so a plain std::max(accumulator, value) would drop it.
  FloatImage ref = grey(2, 1, 0.0f), test = ref;
  test.pixels[0] = kNaNf;
  test.pixels[1] = 5.0f;
  EXPECT_TRUE(std::isnan(max_abs_error(ref, test)));
  EXPECT_TRUE(std::isnan(mean_abs_error(ref, test)));
  EXPECT_THROW(max_abs_error(grey(2, 1, 0), grey(1, 2, 0)), std::invalid_argument);
}

// ---- non-finite counts

TEST(MetricsNonFinite, CountsEachKind) {
  FloatImage img(3, 1, 4);
  img.pixels = {kNaNf, kInff, -kInff, 1.0f,  //
                -0.5f, -0.0f, 0.0f, kNaNf,   // a NaN in alpha counts too
                -1e-30f, 2.0f, 3.0f, 1.0f};
  const NonFinite n = count_non_finite(img);
  EXPECT_EQ(n.nan, 2u);
  EXPECT_EQ(n.inf, 2u);
  EXPECT_EQ(n.negative, 2u);  // -0.5 and -1e-30; -0.0 is not negative, -inf is counted as inf
  const NonFinite clean = count_non_finite(ramp(8, 8));
  EXPECT_EQ(clean.nan + clean.inf + clean.negative, 0u);
}

// ---- chromaticity

TEST(MetricsChromaticity, GreyAgainstBrighterGreyIsZero) {
  EXPECT_NEAR(max_chromaticity_shift(grey(4, 4, 0.2f), grey(4, 4, 0.8f)), 0.0, 1e-12);
  EXPECT_NEAR(max_chromaticity_shift(solid(4, 4, 0.2f, 0.2f, 0.2f), solid(4, 4, 5.0f, 5.0f, 5.0f)), 0.0, 1e-12);
}

TEST(MetricsChromaticity, TintedWhiteKnownShift) {
  // ref (1, 1, 1): X = 0.95047, Y = 1.0000001, Z = 1.08883, X + 15Y + 3Z = 19.2169615,
  //   u' = 4X / 19.2169615 = 0.1978398, v' = 9Y / 19.2169615 = 0.4683363 (D65 white).
  // test (1, 1, 0.5): X = 0.8602513, Y = 0.9639126, Z = 0.6136780, X + 15Y + 3Z = 17.1599741,
  //   u' = 0.2005251, v' = 0.5055493.
  // Distance: hypot(0.0026853, 0.0372130) = 0.0373098.
  const ChromaticityShift s = chromaticity_shift(solid(4, 4, 1, 1, 1), solid(4, 4, 1, 1, 0.5f));
  EXPECT_NEAR(s.max, 0.0373098, 1e-6);
  EXPECT_NEAR(s.mean, 0.0373098, 1e-6);
  EXPECT_EQ(s.pixels, 16u);
  EXPECT_EQ(s.skipped, 0u);
  // Intensity does not matter: the same tint at a tenth of the brightness.
  EXPECT_NEAR(max_chromaticity_shift(solid(4, 4, 0.1f, 0.1f, 0.1f), solid(4, 4, 0.1f, 0.1f, 0.05f)), 0.0373098,
              1e-6);
}

TEST(MetricsChromaticity, MaxMeanRoiAndFloor) {
  // Left half tinted, right half untouched, bottom row black in the test (skipped).
  FloatImage ref = solid(4, 4, 1, 1, 1), test = ref;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 2; ++x) test.at(x, y, 2) = 0.5f;
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t c = 0; c < 3; ++c) test.at(x, 3, c) = 0.0f;
  const ChromaticityShift s = chromaticity_shift(ref, test);
  EXPECT_EQ(s.pixels, 12u);
  EXPECT_EQ(s.skipped, 4u);
  EXPECT_NEAR(s.max, 0.0373098, 1e-6);
  EXPECT_NEAR(s.mean, 0.0373098 / 2.0, 1e-6);
  EXPECT_NEAR(max_chromaticity_shift(ref, test, Roi{0.5, 0.0, 1.0, 1.0}), 0.0, 1e-12);
  // Only black pixels in the ROI: nothing to measure.
  EXPECT_THROW(chromaticity_shift(ref, test, Roi{0.0, 0.75, 1.0, 1.0}), std::invalid_argument);
  // The floor is a parameter: a dim tint is skipped at the default and measured below it.
  EXPECT_THROW(chromaticity_shift(grey(2, 2, 5e-4f), grey(2, 2, 5e-4f)), std::invalid_argument);
  EXPECT_EQ(chromaticity_shift(grey(2, 2, 5e-4f), grey(2, 2, 5e-4f), Roi{}, 1e-4).pixels, 4u);
}

TEST(MetricsChromaticity, NaNPropagates) {
  FloatImage test = solid(2, 1, 1, 1, 1);
  test.at(0, 0, 1) = kNaNf;
  EXPECT_TRUE(std::isnan(max_chromaticity_shift(solid(2, 1, 1, 1, 1), test)));
}

// ---- banding

TEST(MetricsBanding, SmoothRampIsZero) {
  EXPECT_NEAR(banding_index(ramp(256, 4)), 0.0, 1e-9);
  // Slope and offset do not matter.
  FloatImage steep = ramp(256, 4);
  for (float& v : steep.pixels) v = 1000.0f * v + 5.0f;
  EXPECT_NEAR(banding_index(steep), 0.0, 1e-6);
}

TEST(MetricsBanding, QuantisedRampReadsBandWidth) {
  // 256 pixels quantised to L levels: bands P = 256 / L pixels wide, each run of 16 steps holds
  // 16 / P equal jumps, so the index is exactly 1 - 1/P up to the window (P = 16).
  EXPECT_NEAR(banding_index(ramp(256, 4, 128)), 1.0 - 1.0 / 2, 1e-9);
  EXPECT_NEAR(banding_index(ramp(256, 4, 64)), 1.0 - 1.0 / 4, 1e-9);
  EXPECT_NEAR(banding_index(ramp(256, 4, 32)), 1.0 - 1.0 / 8, 1e-9);
  EXPECT_NEAR(banding_index(ramp(256, 4, 16)), 1.0 - 1.0 / 16, 1e-9);
  // Bands wider than the window saturate at 1 - 1/w.
  EXPECT_NEAR(banding_index(ramp(256, 4, 4)), 1.0 - 1.0 / 16, 1e-9);
  // A wider window tells wider bands apart.
  BandingOptions wide;
  wide.window = 64;
  EXPECT_NEAR(banding_index(ramp(256, 4, 8), Roi{}, wide), 1.0 - 1.0 / 32, 1e-9);
}

TEST(MetricsBanding, MonotoneInLevels) {
  double previous = -1.0;
  for (uint32_t levels : {256u, 200u, 128u, 100u, 64u, 50u, 32u, 20u, 16u}) {
    const double b = banding_index(ramp(256, 2, levels));
    EXPECT_GT(b, previous) << levels << " levels";
    previous = b;
  }
  EXPECT_LE(banding_index(ramp(256, 2, 16)), banding_index(ramp(256, 2, 8)) + 1e-12);
}

TEST(MetricsBanding, SmoothCurvesStayNearTheFloor) {
  // Exponential falloff over 40 pixels: no quantisation, index well below 2-pixel bands (0.5).
  FloatImage img(256, 2, 1);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 256; ++x) img.at(x, y, 0) = float(std::exp(-double(x) / 40.0));
  const double b = banding_index(img);
  EXPECT_LT(b, 0.03);
  EXPECT_GT(b, 0.0);
}

TEST(MetricsBanding, AxesAndChannels) {
  const FloatImage vertical = transpose(ramp(256, 32, 32));  // 32 wide, 256 tall
  BandingOptions rows, cols;
  rows.axis = BandingAxis::rows;
  cols.axis = BandingAxis::columns;
  EXPECT_EQ(banding_index(vertical, Roi{}, rows), 0.0);  // rows are flat: no gradient, no bands
  // Too short along the only measured axis.
  EXPECT_THROW(banding_index(transpose(ramp(256, 4, 32)), Roi{}, rows), std::invalid_argument);
  EXPECT_NEAR(banding_index(vertical, Roi{}, cols), 0.875, 1e-9);
  EXPECT_NEAR(banding_index(vertical), 0.875, 1e-9);  // both: flat rows add no energy

  // A quantised ramp in red only; blue stays flat.
  const FloatImage q = ramp(64, 2, 16);
  FloatImage rgb(64, 2, 3);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      rgb.at(x, y, 0) = q.at(x, y, 0);
      rgb.at(x, y, 2) = 0.5f;
    }
  BandingOptions red, blue;
  red.channel = 0;
  blue.channel = 2;
  EXPECT_NEAR(banding_index(rgb, Roi{}, red), 0.75, 1e-9);  // P = 4
  EXPECT_NEAR(banding_index(rgb), 0.75, 1e-9);               // luminance: red scaled by 0.2126
  EXPECT_EQ(banding_index(rgb, Roi{}, blue), 0.0);
}

TEST(MetricsBanding, RoiSelectsTheBandedPart) {
  // Left half smooth, right half quantised (bands of 8).
  FloatImage img = ramp(128, 2);
  const FloatImage q = ramp(128, 2, 16);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 64; x < 128; ++x) img.at(x, y, 0) = q.at(x, y, 0);
  EXPECT_NEAR(banding_index(img, Roi{0.0, 0.0, 0.5, 1.0}), 0.0, 1e-9);
  EXPECT_NEAR(banding_index(img, Roi{0.5, 0.0, 1.0, 1.0}), 0.875, 1e-9);
}

TEST(MetricsBanding, RejectsBadArguments) {
  EXPECT_THROW(banding_index(ramp(16, 16)), std::invalid_argument);  // 16 pixels: 15 steps < 16
  EXPECT_NO_THROW(banding_index(ramp(17, 1)));
  BandingOptions bad;
  bad.channel = 1;
  EXPECT_THROW(banding_index(ramp(64, 2), Roi{}, bad), std::invalid_argument);
  bad.channel = -2;
  EXPECT_THROW(banding_index(ramp(64, 2), Roi{}, bad), std::invalid_argument);
  BandingOptions tiny;
  tiny.window = 1;
  EXPECT_THROW(banding_index(ramp(64, 2), Roi{}, tiny), std::invalid_argument);
}

// ---- flicker

TEST(MetricsFlicker, IdenticalFramesAreStable) {
  const std::vector<FloatImage> frames(5, ramp(8, 8));
  EXPECT_EQ(flicker(frames), 0.0);
  const std::vector<FloatImage> colour(3, solid(4, 4, 0.3f, 0.7f, 0.1f));
  EXPECT_EQ(flicker(colour), 0.0);
  // A NaN in one frame is not averaged away.
  std::vector<FloatImage> broken(3, grey(2, 2, 1.0f));
  broken[1].pixels[0] = kNaNf;
  EXPECT_TRUE(std::isnan(flicker(broken)));
}

TEST(MetricsFlicker, AlternatingFramesKnownValue) {
  // 1, 3, 1, 3: mean 2, population std 1, relative std 0.5.
  std::vector<FloatImage> frames;
  for (int k = 0; k < 4; ++k) frames.push_back(grey(4, 4, k % 2 ? 3.0f : 1.0f));
  EXPECT_NEAR(flicker(frames), 0.5, 1e-12);
  // 1, 2, 3: mean 2, std sqrt(2/3), relative std sqrt(2/3) / 2 = 0.4082483.
  const std::vector<FloatImage> ramped = {grey(2, 2, 1), grey(2, 2, 2), grey(2, 2, 3)};
  EXPECT_NEAR(flicker(ramped), std::sqrt(2.0 / 3.0) / 2.0, 1e-12);
  // Relative: scaling every frame changes nothing.
  std::vector<FloatImage> bright;
  for (int k = 0; k < 4; ++k) bright.push_back(solid(2, 2, k % 2 ? 300.0f : 100.0f, 0, 0));
  EXPECT_NEAR(flicker(bright), 0.5, 1e-12);
}

TEST(MetricsFlicker, AveragesOverRoiAndSkipsBlack) {
  // Columns 0-1 alternate 1/3, columns 2-3 are constant, columns 4-5 are black (skipped).
  std::vector<FloatImage> frames;
  for (int k = 0; k < 2; ++k) {
    FloatImage f = grey(6, 2, 0.0f);
    for (uint32_t y = 0; y < 2; ++y) {
      f.at(0, y, 0) = f.at(1, y, 0) = k ? 3.0f : 1.0f;
      f.at(2, y, 0) = f.at(3, y, 0) = 2.0f;
    }
    frames.push_back(f);
  }
  EXPECT_NEAR(flicker(frames), 0.25, 1e-12);                           // (0.5 + 0) / 2 over counted
  EXPECT_NEAR(flicker(frames, Roi{0.0, 0.0, 1.0 / 3.0, 1.0}), 0.5, 1e-12);
  EXPECT_EQ(flicker(frames, Roi{1.0 / 3.0, 0.0, 2.0 / 3.0, 1.0}), 0.0);
  EXPECT_THROW(flicker(frames, Roi{2.0 / 3.0, 0.0, 1.0, 1.0}), std::invalid_argument);
}

TEST(MetricsFlicker, RejectsBadInput) {
  EXPECT_THROW(flicker({}), std::invalid_argument);
  EXPECT_THROW(flicker({grey(2, 2, 1)}), std::invalid_argument);
  EXPECT_THROW(flicker({grey(2, 2, 1), grey(2, 3, 1)}), std::invalid_argument);
  EXPECT_THROW(flicker({grey(2, 2, 1), grey(2, 2, 1)}, Roi{}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace gib::metrics
