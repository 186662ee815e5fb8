// pixel_denoise's temporal history and its anti-lag (the CPU mirror,
// renderer/techniques/probe_volume/pixel_denoise/pixel_denoise_temporal.h), on 4096 independent
// ray pixels fed a Gaussian-noisy estimate of a known signal L with relative standard deviation
// 0.1 (var_now = (0.1 L)^2, the noise estimate the spatial filter hands the temporal step):
//   - a still signal keeps the variance reduction of the 16-frame history: the anti-lag's band
//     (3 standard deviations of the slow - fast difference) clamps 0.27% of the pixels a frame,
//     each back to the fast history's 4 frames: +9% variance (1/31 -> 0.035 of one frame's);
//   - so does a heavy-tailed one (a window of 25 rays, 5% of them on a source 20x brighter: in
//     28% of the frames no ray of the window sees it, and its spatial variance is far too low;
//     its mean over frames holds the true variance);
//   - a step of the signal (L 1 -> 0.5) is followed within a few fast-history frames, where the
//     history alone still holds (15/16)^n of the step;
//   - lighting-change's sunset (the signal falls 4.5x over 60 frames) lags by the band, not by
//     the 16 frames of the history.
// And the shader against the mirror: pixel_denoise on lavapipe (the closed box, still camera,
// one ray per pixel) fed a per-pixel random Y0 (graph override of pixel_sh) whose level steps
// down 4x, its slow and fast histories compared with the mirror's, frame by frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "harness/case.h"
#include "harness/case_render.h"
#include "renderer/codecs/packed_float.h"
#include "renderer/codecs/ycocg_sh.h"
#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise_shared.h"
#include "renderer/techniques/probe_volume/pixel_denoise/pixel_denoise_temporal.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

// Deterministic Gaussian samples (PCG-style LCG, Box-Muller).
struct Gauss {
  uint64_t state = 1;
  double uniform() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (double(state >> 11) + 0.5) / 9007199254740992.0;
  }
  double operator()() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(6.283185307179586 * uniform()); }
};

constexpr int kPixels = 4096;
constexpr double kNoise = 0.1;  // relative standard deviation of one frame's filtered estimate

struct Pixels {
  std::vector<PvDenoiseHistory> h = std::vector<PvDenoiseHistory>(kPixels);
  Gauss gauss;
  PvDenoiseTemporal t;
  // One frame at signal level L.
  void frame(double level) {
    const float var = float(kNoise * kNoise * level * level);
    for (PvDenoiseHistory& p : h)
      p = pv_denoise_temporal(p, {float(level * (1.0 + kNoise * gauss())), var, true}, t);
  }
  double mean() const {
    double m = 0;
    for (const PvDenoiseHistory& p : h) m += p.y0;
    return m / kPixels;
  }
  double variance() const {
    const double m = mean();
    double v = 0;
    for (const PvDenoiseHistory& p : h) v += (p.y0 - m) * (p.y0 - m);
    return v / kPixels;
  }
};

Pixels still_pixels(float sigma, int frames) {
  Pixels px;
  px.t.sigma = sigma;
  for (int f = 0; f < frames; ++f) px.frame(1.0);
  return px;
}

TEST(ProbeVolumeDenoise, StillSignalKeepsTheHistorysVarianceReduction) {
  // The 16-frame exponential average at its cap: variance 1 / (2 x 16 - 1) of one frame's.
  const Pixels off = still_pixels(0.0f, 128);
  const Pixels on = still_pixels(3.0f, 128);
  const double one_frame = kNoise * kNoise;
  EXPECT_NEAR(off.variance() / one_frame, 1.0 / 31.0, 0.004);
  EXPECT_LT(on.variance() / off.variance(), 1.12) << "anti-lag adds noise to a still signal";
  EXPECT_NEAR(on.mean(), 1.0, 0.005);
}

TEST(ProbeVolumeDenoise, HeavyTailedStillSignalKeepsTheHistorysVarianceReduction) {
  double mean[2], sd[2];
  for (int k = 0; k < 2; ++k) {
    PvDenoiseTemporal t;
    t.sigma = k == 0 ? 0.0f : 3.0f;
    std::vector<PvDenoiseHistory> h(kPixels);
    Gauss rng;
    double sum = 0, sum2 = 0;
    for (int f = 0; f < 160; ++f)
      for (PvDenoiseHistory& p : h) {
        double s = 0, s2 = 0;
        for (int ray = 0; ray < 25; ++ray) {
          const double v = rng.uniform() < 0.05 ? 20.0 : 1.0;
          s += v, s2 += v * v;
        }
        const double m = s / 25, var = (s2 / 25 - m * m) / 24;
        p = pv_denoise_temporal(p, {float(m), float(var), true}, t);
        if (f >= 64) sum += p.y0, sum2 += double(p.y0) * p.y0;
      }
    const double n = double(kPixels) * 96;
    mean[k] = sum / n;
    sd[k] = std::sqrt(sum2 / n - mean[k] * mean[k]);
  }
  EXPECT_NEAR(mean[1], 1.95, 0.01);  // 0.95 x 1 + 0.05 x 20
  EXPECT_LT(sd[1] / sd[0], 1.03) << "anti-lag adds noise where a window mostly misses the source";
}

TEST(ProbeVolumeDenoise, StepIsFollowedWithinTheFastHistory) {
  Pixels off = still_pixels(0.0f, 64);
  Pixels on = still_pixels(3.0f, 64);
  for (int f = 0; f < 8; ++f) {
    off.frame(0.5);
    on.frame(0.5);
  }
  // History alone: 0.5 + 0.5 (15/16)^8 = 0.798 after 8 frames.
  EXPECT_NEAR(off.mean(), 0.5 + 0.5 * std::pow(15.0 / 16.0, 8.0), 0.005);
  // Anti-lag: the fast history (4 frames) holds 0.5 (3/4)^8 = 0.05 of the step, the slow one
  // sits within the band above it: 0.567 measured.
  EXPECT_LT(on.mean(), 0.59);
  for (int f = 0; f < 8; ++f) on.frame(0.5);
  EXPECT_LT(on.mean(), 0.55) << "16 frames after the step (0.541 measured)";
}

TEST(ProbeVolumeDenoise, SunsetLagsByTheBandNotTheHistory) {
  for (float sigma : {0.0f, 3.0f}) {
    Pixels px = still_pixels(sigma, 60);
    double level = 1.0;
    for (int f = 1; f <= 60; ++f) {
      level = std::pow(4.5, -f / 60.0);
      px.frame(level);
    }
    const double ratio = px.mean() / level;
    if (sigma == 0.0f)
      EXPECT_NEAR(ratio, 1.56, 0.02) << "the 16-frame history's lag at a 2.5 % a frame fall";
    else
      EXPECT_LT(ratio, 1.22) << "anti-lag (1.18 measured)";
  }
}

// ---- the shader against the mirror

struct Surface {
  float px, py, pz, depth;
  float nx, ny, nz;
  bool translucent;
};

// pv_surface_at and pv_bilateral (pv_surface.glsl) on the G-buffer read back.
std::vector<Surface> surfaces(const CaseRender& r, size_t pixels) {
  std::vector<Surface> s(pixels);
  const float* pos = reinterpret_cast<const float*>(r.read.at("gbuffer_position").data());
  const uint16_t* nrm = reinterpret_cast<const uint16_t*>(r.read.at("gbuffer_normal").data());
  const uint16_t* emi = reinterpret_cast<const uint16_t*>(r.read.at("gbuffer_emissive").data());
  for (size_t i = 0; i < pixels; ++i) {
    s[i] = {pos[i * 4], pos[i * 4 + 1], pos[i * 4 + 2], pos[i * 4 + 3], 0, 0, 0, false};
    const float n[3] = {codecs::half_to_float(nrm[i * 4]), codecs::half_to_float(nrm[i * 4 + 1]),
                        codecs::half_to_float(nrm[i * 4 + 2])};
    const float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (std::isfinite(len2) && len2 > 0.25f) {
      const float k = 1.0f / std::sqrt(len2);
      s[i].nx = n[0] * k, s[i].ny = n[1] * k, s[i].nz = n[2] * k;
    }
    s[i].translucent = codecs::half_to_float(emi[i * 4 + 3]) > 0.0f;
  }
  return s;
}

float bilateral(const Surface& a, const Surface& b) {
  if (b.depth == 0.0f || a.translucent != b.translucent) return 0.0f;
  const float plane = std::abs((b.px - a.px) * a.nx + (b.py - a.py) * a.ny + (b.pz - a.pz) * a.nz) / (0.02f * a.depth);
  float wn = std::max(a.nx * b.nx + a.ny * b.ny + a.nz * b.nz, 0.0f);
  wn *= wn;
  wn *= wn;
  return std::max(0.0f, 1.0f - plane) * wn * wn;
}

// Y0 of ray pixel i in frame f: the level (1, then 1/4 from frame 8) times a per-pixel random
// factor in [0.5, 1.5), stored through the 64-bit codec (Y1 and chroma 0).
constexpr uint32_t kStepFrame = 8, kFrames = 14;
std::vector<uint8_t> pixel_sh_frame(uint32_t f, size_t pixels) {
  std::vector<uint8_t> out(pixels * 8);
  Gauss rng{uint64_t(f) * 7919u + 17u};
  for (size_t i = 0; i < pixels; ++i) {
    const float level = f < kStepFrame ? 1.0f : 0.25f;
    const auto w = codecs::pack_ycocg_sh({float(level * (0.5 + rng.uniform())), 0, 0, 0, 0, 0});
    std::memcpy(out.data() + i * 8, w.data(), 8);
  }
  return out;
}

float decoded_y0(const std::vector<uint8_t>& sh, size_t i) {
  std::array<uint32_t, 2> w;
  std::memcpy(w.data(), sh.data() + i * 8, 8);
  return codecs::unpack_ycocg_sh(w)[0];
}

class ProbeVolumeDenoiseGpu : public test::GpuTest {};

TEST_F(ProbeVolumeDenoiseGpu, ShaderFollowsTheMirrorThroughAStep) {
  Case c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/white-furnace-closed-box.json");
  c.width = 32;
  c.height = 18;
  c.frames = kFrames;
  TechniqueRun run;
  for (const TechniqueRun& t : c.techniques)
    if (t.technique == "probe-volume" && t.label.empty()) run = t;
  run.frames = kFrames;
  run.options["pixel_divisor"] = 1;  // one ray pixel per pixel: the G-buffer read back is the filter's
  const size_t pixels = size_t(c.width) * c.height;
  std::vector<std::vector<uint8_t>> input;
  RunHooks hooks;
  for (uint32_t f = 0; f < kFrames; ++f) {
    input.push_back(pixel_sh_frame(f, pixels));
    hooks.overrides.push_back({"hit_lighting", "pixel_sh", input.back(), f, f});
  }
  hooks.read = {"pixel_history_y", "pixel_history_c", "pixel_history_fast", "gbuffer_position", "gbuffer_normal",
                "gbuffer_emissive"};
  hooks.read_frames = kFrames;
  const CaseRender r = render_case_hooked(gpu(), c, run, "low", 0, hooks);
  ASSERT_EQ(r.read_before.size(), size_t(kFrames - 1));
  const std::vector<Surface> surf = surfaces(r, pixels);
  const int w = int(c.width), h = int(c.height), radius = 2;
  PvDenoiseTemporal t;
  std::vector<PvDenoiseHistory> cpu(pixels);
  size_t clamped = 0, compared = 0;
  for (uint32_t f = 0; f < kFrames; ++f) {
    const auto& reads = f + 1 < kFrames ? r.read_before[f] : r.read;
    const float* gy = reinterpret_cast<const float*>(reads.at("pixel_history_y").data());
    const float* gc = reinterpret_cast<const float*>(reads.at("pixel_history_c").data());
    const float* gf = reinterpret_cast<const float*>(reads.at("pixel_history_fast").data());
    std::vector<PvDenoiseHistory> next(pixels);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        const Surface& a = surf[i];
        if (a.depth == 0.0f) continue;
        float sw = 0, sw2 = 0, swy = 0, swy2 = 0;
        for (int dy = -radius; dy <= radius; ++dy)
          for (int dx = -radius; dx <= radius; ++dx) {
            const int x2 = x + dx, y2 = y + dy;
            if (x2 < 0 || y2 < 0 || x2 >= w || y2 >= h) continue;
            const size_t j = size_t(y2) * w + x2;
            const float wt = (dx == 0 && dy == 0) ? 1.0f : bilateral(a, surf[j]);
            if (wt <= 0.0f) continue;
            const float v = decoded_y0(input[f], j);
            sw += wt, sw2 += wt * wt, swy += wt * v, swy2 += wt * v * v;
          }
        const float mean = swy / sw, n_eff = sw * sw / sw2;
        const float var = n_eff > 1.0f ? std::max(swy2 / sw - mean * mean, 0.0f) / (n_eff - 1.0f) : 0.0f;
        next[i] = pv_denoise_temporal(cpu[i], {mean, var, n_eff >= glsl::kPvAntiLagMinSamples}, t);
        if (next[i].frames < std::min(cpu[i].frames + 1.0f, t.n_max)) ++clamped;
        // Pixels near the noise estimate's sample threshold may decide differently in float.
        if (std::abs(n_eff - glsl::kPvAntiLagMinSamples) < 0.05f) continue;
        ++compared;
        EXPECT_NEAR(gy[i * 4], next[i].y0, 2e-4f * next[i].y0 + 1e-6f) << "Y0, frame " << f << " pixel " << x << "," << y;
        EXPECT_NEAR(gf[i * 4], next[i].fast, 2e-4f * next[i].fast + 1e-6f) << "fast, frame " << f << " pixel " << x << "," << y;
        EXPECT_NEAR(gf[i * 4 + 1], next[i].var_mean, 1e-3f * next[i].var_mean + 1e-9f)
            << "mean var_now, frame " << f << " pixel " << x << "," << y;
        EXPECT_EQ(gf[i * 4 + 2], next[i].var_frames) << "frame " << f << " pixel " << x << "," << y;
        EXPECT_EQ(gc[i * 4 + 2], next[i].frames) << "frames, frame " << f << " pixel " << x << "," << y;
      }
    cpu = next;
  }
  EXPECT_GT(compared, pixels * kFrames / 2);
  EXPECT_GT(clamped, 0u) << "the step must reach the anti-lag";
}

}  // namespace
}  // namespace gib
