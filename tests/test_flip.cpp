// FLIP: reproduces the reference tool's results on data/flip-vectors (every run of every
// pair), plus known-answer and sanity tests, and the magma colour map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "harness/image_io.h"
#include "metrics/colormap.h"
#include "metrics/flip.h"

#ifndef GIB_SOURCE_DIR
#error "GIB_SOURCE_DIR must point at the source tree"
#endif

namespace gib {
namespace {

using json = nlohmann::json;

const std::string kVectorDir = std::string(GIB_SOURCE_DIR) + "/data/flip-vectors";

// PNG: 8-bit, first three channels, decoded as the tool does. EXR: float, first three.
FloatImage load_image(const std::string& path) {
  const bool exr = std::filesystem::path(path).extension() == ".exr";
  if (!exr) {
    const Rgb8Image in = read_rgb8(path);
    return srgb8_to_linear(in.rgb, in.width, in.height);
  }
  FloatImage all = read_image(path);
  if (all.channels < 3) throw std::runtime_error(path + ": fewer than 3 channels");
  FloatImage img(all.width, all.height, 3);
  for (size_t i = 0; i < size_t(all.width) * all.height; ++i)
    for (uint32_t c = 0; c < 3; ++c) img.pixels[i * 3 + c] = all.pixels[i * all.channels + c];
  return img;
}

// Options from the tool's command line as recorded in expected.json.
FlipOptions options_from_run(const json& run, bool hdr) {
  FlipOptions o;
  o.mode = hdr ? FlipOptions::Mode::hdr : FlipOptions::Mode::ldr;
  std::istringstream ss(run.at("command").get<std::string>());
  std::vector<std::string> tok;
  for (std::string t; ss >> t;) tok.push_back(t);
  for (size_t i = 0; i + 1 < tok.size(); ++i) {
    const std::string& t = tok[i];
    if (t == "-ppd" || t == "--pixels-per-degree") o.ppd = std::stod(tok[i + 1]);
    else if (t == "-tm" || t == "--tone-mapper") o.tonemapper = tok[i + 1];
    else if (t == "-cstart" || t == "--start-exposure") o.start_exposure = std::stod(tok[i + 1]);
    else if (t == "-cstop" || t == "--stop-exposure") o.stop_exposure = std::stod(tok[i + 1]);
    else if (t == "-n" || t == "--num-exposures") o.num_exposures = std::stoi(tok[i + 1]);
    else if ((t == "-vc" || t == "--viewing-conditions") && i + 3 < tok.size())
      o.ppd = flip_ppd(std::stod(tok[i + 1]), std::stod(tok[i + 2]), std::stod(tok[i + 3]));
  }
  if (run.contains("tone_mapper")) o.tonemapper = run["tone_mapper"].get<std::string>();
  // The tool works with the float32 ppd; expected.json records it.
  if (run.contains("ppd")) {
    EXPECT_NEAR(o.ppd, run["ppd"].get<double>(), 1e-5) << run["command"];
  }
  return o;
}

double printed(const json& run, const char* key) { return std::stod(run.at(key).get<std::string>()); }

TEST(FlipVectors, EveryRunMatchesReferenceTool) {
  ASSERT_TRUE(std::filesystem::exists(kVectorDir + "/expected.json")) << kVectorDir;
  std::ifstream f(kVectorDir + "/expected.json");
  const json doc = json::parse(f);
  ASSERT_TRUE(doc.contains("pairs"));
  double worst = 0;
  std::string worst_run;
  int runs = 0;
  for (const json& pair : doc["pairs"]) {
    const std::string name = pair.at("name");
    const bool hdr = pair.at("mode") == "hdr";
    const FloatImage ref = load_image(kVectorDir + "/" + pair.at("reference").get<std::string>());
    const FloatImage test = load_image(kVectorDir + "/" + pair.at("test").get<std::string>());
    ASSERT_EQ(ref.width, pair.at("width").get<uint32_t>()) << name;
    ASSERT_EQ(ref.height, pair.at("height").get<uint32_t>()) << name;
    for (const json& run : pair.at("runs")) {
      const std::string id = name + "/" + run.at("tag").get<std::string>();
      const FlipOptions opt = options_from_run(run, hdr);
      const FlipResult r = flip(ref, test, opt);
      ++runs;
      const double exact = run.at("mean_exact").get<double>();
      const double diff = std::fabs(r.mean - exact);
      if (diff > worst) worst = diff, worst_run = id;
      EXPECT_NEAR(r.mean, exact, 2e-4) << id;
      // The tool's per-pixel maps agree with an independent float64 implementation to 6e-4
      // at worst; percentiles, extremes and probes are single pixel values.
      EXPECT_NEAR(r.min, run.at("min_exact").get<double>(), 1e-3) << id;
      EXPECT_NEAR(r.max, run.at("max_exact").get<double>(), 1e-3) << id;
      EXPECT_NEAR(r.weighted_median, printed(run, "weighted_median_printed"), 1e-3) << id;
      EXPECT_NEAR(r.weighted_q1, printed(run, "weighted_q1_printed"), 1e-3) << id;
      EXPECT_NEAR(r.weighted_q3, printed(run, "weighted_q3_printed"), 1e-3) << id;
      const uint32_t cx = ref.width / 2, cy = ref.height / 2;
      EXPECT_NEAR(r.error_map.at(cx, cy, 0), run.at("center_pixel").get<double>(), 1e-3) << id;
      EXPECT_NEAR(r.error_map.at(0, 0, 0), run.at("corner_pixel").get<double>(), 1e-3) << id;
      EXPECT_EQ(r.error_map.channels, 1u);
      if (hdr) {
        if (run.contains("start_exposure")) {
          EXPECT_NEAR(r.start_exposure, run["start_exposure"].get<double>(), 1e-4) << id;
        }
        if (run.contains("stop_exposure")) {
          EXPECT_NEAR(r.stop_exposure, run["stop_exposure"].get<double>(), 1e-4) << id;
        }
        if (run.contains("num_exposures")) {
          EXPECT_EQ(r.num_exposures, run["num_exposures"].get<int>()) << id;
        }
      }
      std::printf("  %-40s mean %.9f  exact %.9f  |diff| %.2e  median %.6f (tool %s)\n", id.c_str(), r.mean, exact,
                  diff, r.weighted_median, run.at("weighted_median_printed").get<std::string>().c_str());
    }
  }
  EXPECT_GT(runs, 0);
  std::printf("FLIP vectors: %d runs, worst |mean - mean_exact| = %.3e (%s)\n", runs, worst, worst_run.c_str());
}

// ---------------------------------------------------------------- synthetic images

FloatImage gradient(uint32_t w, uint32_t h) {
  FloatImage img(w, h, 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      img.at(x, y, 0) = float(x) / float(w - 1);
      img.at(x, y, 1) = float(y) / float(h - 1);
      img.at(x, y, 2) = 0.5f * (img.at(x, y, 0) + img.at(x, y, 1));
    }
  return img;
}

FloatImage with_noise(const FloatImage& base, float amplitude, uint32_t seed, bool clamp01) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  FloatImage img = base;
  for (float& v : img.pixels) {
    v += amplitude * u(rng);
    if (clamp01) v = std::clamp(v, 0.0f, 1.0f);
  }
  return img;
}

FlipOptions hdr_options() {
  FlipOptions o;
  o.mode = FlipOptions::Mode::hdr;
  return o;
}

TEST(FlipSanity, IdenticalImagesGiveZero) {
  const FloatImage a = with_noise(gradient(48, 40), 0.2f, 1, true);
  for (const FlipOptions& o : {FlipOptions{}, hdr_options()}) {
    FlipResult r = flip(a, a, o);
    EXPECT_EQ(r.mean, 0.0);
    EXPECT_EQ(r.max, 0.0);
    EXPECT_EQ(r.weighted_median, 0.0);
    EXPECT_EQ(r.error_map.width, 48u);
    EXPECT_EQ(r.error_map.height, 40u);
    EXPECT_EQ(r.error_map.channels, 1u);
  }
}

TEST(FlipSanity, SizeMismatchAndBadOptionsThrow) {
  EXPECT_THROW(flip(gradient(16, 16), gradient(16, 17), {}), std::invalid_argument);
  EXPECT_THROW(flip(gradient(16, 16), gradient(17, 16), {}), std::invalid_argument);
  FlipOptions o = hdr_options();
  o.tonemapper = "filmic";
  EXPECT_THROW(flip(gradient(16, 16), gradient(16, 16), o), std::invalid_argument);
  o = hdr_options();
  o.start_exposure = 2;
  o.stop_exposure = 1;
  EXPECT_THROW(flip(gradient(16, 16), gradient(16, 16), o), std::invalid_argument);
  o = FlipOptions{};
  o.ppd = 0;
  EXPECT_THROW(flip(gradient(16, 16), gradient(16, 16), o), std::invalid_argument);
}

// NOTES section 7's worked example: flat black vs flat white has no feature difference and
// HyAB = 100, so every pixel is (100^0.7 scaled by the remap) ~ 0.96738.
TEST(FlipSanity, BlackVersusWhiteKnownAnswer) {
  FloatImage black(32, 24, 3, 0.0f), white(32, 24, 3, 1.0f);
  FlipResult r = flip(black, white, {});
  EXPECT_NEAR(r.min, 0.967380, 2e-5);
  EXPECT_NEAR(r.max, 0.967380, 2e-5);
  EXPECT_NEAR(r.mean, 0.967380, 2e-5);
  EXPECT_NEAR(r.weighted_median, 0.967380, 2e-5);
}

TEST(FlipSanity, ErrorGrowsWithNoiseAmplitude) {
  const FloatImage base = gradient(96, 64);
  double previous = 0;
  for (float amp : {0.005f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
    FlipResult r = flip(base, with_noise(base, amp, 7, true), {});
    EXPECT_GT(r.mean, previous) << "amplitude " << amp;
    previous = r.mean;
  }
  // HDR likewise (multiplicative noise on a brighter scene).
  FloatImage hbase = gradient(64, 64);
  for (float& v : hbase.pixels) v = 0.01f + 8.0f * v * v;
  previous = 0;
  for (float amp : {0.02f, 0.1f, 0.3f}) {
    FloatImage t = hbase;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (float& v : t.pixels) v *= 1.0f + amp * u(rng);
    FlipResult r = flip(hbase, t, hdr_options());
    EXPECT_GT(r.mean, previous) << "HDR amplitude " << amp;
    previous = r.mean;
  }
}

// One changed pixel: the map is zero outside the filters' reach (CSF radius 10 and feature
// radius 9 at the default ppd), and largest at the pixel itself.
TEST(FlipSanity, SinglePixelDifferenceIsLocalised) {
  const uint32_t w = 64, h = 64, px = 30, py = 33;
  FloatImage a(w, h, 3, 0.4f), b = a;
  b.at(px, py, 0) = 1.0f;
  b.at(px, py, 1) = 0.1f;
  FlipResult r = flip(a, b, {});
  float peak = -1;
  uint32_t peak_x = 0, peak_y = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const float e = r.error_map.at(x, y, 0);
      const int dx = std::abs(int(x) - int(px)), dy = std::abs(int(y) - int(py));
      if (std::max(dx, dy) > 10) {
        EXPECT_EQ(e, 0.0f) << x << "," << y;
      }
      if (e > peak) peak = e, peak_x = x, peak_y = y;
    }
  EXPECT_GT(peak, 0.1f);
  EXPECT_EQ(peak_x, px);
  EXPECT_EQ(peak_y, py);
  EXPECT_GT(r.error_map.at(px + 1, py, 0), 0.0f);
}

TEST(FlipSanity, HdrAutomaticExposureRange) {
  // Luminance of a grey pixel equals its value: L_max = 16, upper median = 0.25.
  FloatImage ref(4, 1, 3);
  const float vals[4] = {0.125f, 0.25f, 4.0f, 16.0f};
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t c = 0; c < 3; ++c) ref.at(x, 0, c) = vals[x];
  FlipOptions o = hdr_options();
  FlipResult r = flip(ref, ref, o);
  const double lsum = 0.2126 + 0.7152 + 0.0722;  // ~1
  EXPECT_NEAR(r.start_exposure, std::log2(2.1188723 / (16.0 * lsum)), 1e-5);
  EXPECT_NEAR(r.stop_exposure, std::log2(2.1188723 / (4.0 * lsum)), 1e-5);
  EXPECT_EQ(r.num_exposures, 2);
  o.tonemapper = "reinhard";
  r = flip(ref, ref, o);
  EXPECT_NEAR(r.start_exposure, std::log2(0.85 / 0.15 / 16.0), 1e-5);
  o.tonemapper = "hable";
  r = flip(ref, ref, o);
  EXPECT_NEAR(r.start_exposure, std::log2(3.1277493 / 16.0), 1e-5);
  // One of start/stop given: the other is automatic; count follows the range.
  o.tonemapper = "aces";
  o.start_exposure = -6.0;
  r = flip(ref, ref, o);
  EXPECT_EQ(r.start_exposure, -6.0);
  EXPECT_NEAR(r.stop_exposure, std::log2(2.1188723 / 4.0), 1e-5);
  EXPECT_EQ(r.num_exposures, int(std::ceil(r.stop_exposure + 6.0)));
}

TEST(FlipSanity, HdrMostlyBlackReferenceUsesTheMedianOfLitPixels) {
  // Five of eight pixels black (a 1-spp render): the median luminance is 0, so the stop
  // exposure comes from the median of the lit pixels {1, 2, 8} = 2.
  FloatImage ref(8, 1, 3);
  const float vals[8] = {0, 0, 0, 0, 0, 1.0f, 2.0f, 8.0f};
  for (uint32_t x = 0; x < 8; ++x)
    for (uint32_t c = 0; c < 3; ++c) ref.at(x, 0, c) = vals[x];
  FlipResult r = flip(ref, ref, hdr_options());
  const double lsum = 0.2126 + 0.7152 + 0.0722;
  EXPECT_NEAR(r.start_exposure, std::log2(2.1188723 / (8.0 * lsum)), 1e-5);
  EXPECT_NEAR(r.stop_exposure, std::log2(2.1188723 / (2.0 * lsum)), 1e-5);
  EXPECT_EQ(r.mean, 0.0);
  // All black: no exposure maps anything to grey; the range must be given.
  EXPECT_THROW(flip(FloatImage(8, 1, 3, 0.0f), ref, hdr_options()), std::invalid_argument);
}

TEST(FlipSanity, PpdAndSrgbDecode) {
  EXPECT_NEAR(flip_ppd(0.7, 0.7, 3840), 67.02064514160156, 1e-5);
  FloatImage lin = srgb8_to_linear({0, 128, 255}, 1, 1);
  EXPECT_EQ(lin.channels, 3u);
  EXPECT_EQ(lin.pixels[0], 0.0f);
  EXPECT_NEAR(lin.pixels[1], 0.2158605, 1e-6);
  EXPECT_EQ(lin.pixels[2], 1.0f);
}

TEST(FlipMagma, LooksLikeMagma) {
  auto lum = [](std::array<float, 3> c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  auto c0 = magma(0.0f), c1 = magma(1.0f), cq = magma(0.25f), ch = magma(0.5f), c3 = magma(0.75f);
  EXPECT_LT(std::max({c0[0], c0[1], c0[2]}), 0.03f);                 // black
  EXPECT_GT(c1[0], 0.9f);                                            // light yellow
  EXPECT_GT(c1[1], 0.9f);
  EXPECT_GT(c1[2], 0.6f);
  EXPECT_LT(c1[2], c1[1]);
  EXPECT_GT(cq[2], cq[0]);                                           // purple: blue > red > green
  EXPECT_GT(cq[0], cq[1]);
  EXPECT_GT(ch[0], ch[2]);                                           // magenta-red
  EXPECT_GT(c3[0], 0.9f);                                            // orange: red > green > blue
  EXPECT_GT(c3[1], c3[2]);
  float prev = -1;
  for (int i = 0; i <= 256; ++i) {
    float l = lum(magma(float(i) / 256.0f));
    EXPECT_GT(l, prev) << i;
    prev = l;
  }
  EXPECT_EQ(magma(-1.0f), c0);
  EXPECT_EQ(magma(2.0f), c1);
  EXPECT_EQ(magma(std::nanf("")), c0);
  FloatImage e(3, 2, 1, 0.5f);
  FloatImage m = magma_error_map(e);
  EXPECT_EQ(m.channels, 3u);
  EXPECT_EQ(m.width, 3u);
  EXPECT_EQ(m.height, 2u);
  EXPECT_EQ(m.at(2, 1, 0), ch[0]);
  FloatImage lin = magma_error_map(e, true);
  EXPECT_LT(lin.at(0, 0, 0), ch[0]);  // decoded values are darker
}

}  // namespace
}  // namespace gib
