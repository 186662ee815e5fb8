// The radiance-cache pre-exposure (renderer/techniques/radiance_cache/exposure/exposure.h): known answers of the
// CPU mirror, and the GPU pass against the mirror on a small rendered image (lavapipe).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/techniques/radiance_cache/exposure/exposure.h"
#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gpu_fixture.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

FloatImage grey(uint32_t w, uint32_t h, float v) {
  FloatImage img(w, h, 4, v);
  for (size_t i = 0; i < img.pixel_count(); ++i) img.pixels[i * 4 + 3] = 1.0f;
  return img;
}

TEST(PreExposureMirror, ConstantLuminanceGivesItsInverse) {
  for (float l : {1.0f, 0.25f, 3000.0f, 6000.0f, 1e-4f}) {
    PreExposure e = compute_pre_exposure(grey(7, 5, l), nullptr, 0.0f);
    EXPECT_NEAR(e.p_now, 1.0f / l, 1e-5f / l) << l;
    EXPECT_EQ(e.p_prev, e.p_now) << l;  // first frame
    EXPECT_NEAR(e.average_luminance, l, 1e-5f * l) << l;
    EXPECT_EQ(e.lit_pixels, 4u) << l;  // 7x5 read at x, y in {0, 4} (kExposureStride 4)
  }
}

TEST(PreExposureMirror, NothingLitGivesOne) {
  static_assert(glsl::kExposureStride == 4, "the pixels below are the ones read");
  FloatImage img = grey(16, 4, 0.0f);
  img.at(0, 0, 0) = -5.0f;                                        // negative luminance: unlit
  img.at(4, 0, 1) = std::numeric_limits<float>::quiet_NaN();      // non-finite: unlit
  img.at(8, 0, 2) = std::numeric_limits<float>::infinity();
  img.at(12, 0, 1) = 1e-11f;                                      // below kExposureMinLuminance
  img.at(1, 1, 1) = 100.0f;                                       // not read (x, y not multiples of 4)
  PreExposure e = compute_pre_exposure(img, nullptr, 0.0f);
  EXPECT_EQ(e.p_now, 1.0f);
  EXPECT_EQ(e.lit_pixels, 0u);
  EXPECT_EQ(e.average_luminance, 0.0f);
  // Disabled: 1 whatever the image.
  PreExposure off = compute_pre_exposure(grey(4, 4, 3000.0f), nullptr, 0.0f, false);
  EXPECT_EQ(off.p_now, 1.0f);
  EXPECT_EQ(off.p_prev, 1.0f);
}

TEST(PreExposureMirror, ClampsToTwoToTheTwenty) {
  EXPECT_EQ(compute_pre_exposure(grey(2, 2, 1e-9f), nullptr, 0.0f).p_now, std::ldexp(1.0f, 20));
  EXPECT_EQ(compute_pre_exposure(grey(2, 2, 1e7f), nullptr, 0.0f).p_now, std::ldexp(1.0f, -20));
}

TEST(PreExposureMirror, LogAverageOfLitPixelsAndLastFrame) {
  // 8x8 read at x, y in {0, 4}: rows 0-3 at 1, rows 4-7 at 4: log-average 2.
  FloatImage img = grey(8, 8, 1.0f);
  for (uint32_t y = 4; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x)
      for (uint32_t c = 0; c < 3; ++c) img.at(x, y, c) = 4.0f;
  EXPECT_NEAR(compute_pre_exposure(img, nullptr, 0.0f).p_now, 0.5f, 1e-6f);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 8; ++x)
      for (uint32_t c = 0; c < 3; ++c) img.at(x, y, c) = 0.0f;  // unlit pixels do not count
  PreExposure e = compute_pre_exposure(img, nullptr, 0.0f);
  EXPECT_NEAR(e.p_now, 0.25f, 1e-6f);
  EXPECT_EQ(e.lit_pixels, 2u);
  // Last frame's colour: per pixel the brighter of the two; p_prev is the stored P.
  FloatImage prev = grey(8, 8, 16.0f);
  e = compute_pre_exposure(img, &prev, 0.125f);
  EXPECT_NEAR(e.p_now, 1.0f / 16.0f, 1e-7f);
  EXPECT_EQ(e.lit_pixels, 4u);
  EXPECT_EQ(e.p_prev, 0.125f);
}

// Writes final_color as a constant (persistent, so the exposure pass reads last frame's copy).
class ConstantFinalColor final : public Pass {
 public:
  explicit ConstantFinalColor(float v) : v_(v) {}
  PassDecl declare(const Scene&, const Settings&) const override {
    ResourceDesc color{Format::rgba32_float, SizeRule::render};
    color.persistent = true;
    return {"constant_final_color", PassKind::transfer, {}, {}, {{"final_color", Access::write, color}}, false};
  }
  void record(RecordContext& ctx) override {
    const float value[4] = {v_, v_, v_, 1.0f};
    ctx.cmd.clear(ctx.image("final_color"), value);
  }

 private:
  float v_;
};

PreExposure read_exposure(Executor& ex) {
  std::vector<uint8_t> raw = ex.read_buffer("exposure");
  float w[glsl::kExposureWords];
  EXPECT_EQ(raw.size(), sizeof(w));
  std::memcpy(w, raw.data(), sizeof(w));
  return {w[glsl::kExposureNow], w[glsl::kExposurePrev], w[glsl::kExposureAverage],
          uint32_t(w[glsl::kExposureLitPixels])};
}

class PreExposureGpu : public test::GpuTest {};

// A sunlit floor, box and sphere under a bright sky, 40x24 (direct_light: sun, shadows, 4 sky
// rays, the sky itself); frame 0 sees direct_light alone, frame 1 also last frame's final_color.
TEST_F(PreExposureGpu, BufferMatchesCpuMirror) {
  Scene scene = parse_scene(nlohmann::json::parse(R"({
    "materials": {"white": {"albedo": [0.7, 0.7, 0.7]}, "red": {"albedo": [0.8, 0.1, 0.1]}},
    "objects": [
      {"primitive": {"type": "quad", "size": [20, 20], "facing": "+y"}, "material": "white"},
      {"primitive": {"type": "box", "size": [1, 1, 1]}, "material": "red", "transform": {"translate": [0, 0.5, 0]}},
      {"primitive": {"type": "sphere", "radius": 0.5}, "material": "white", "transform": {"translate": [1.5, 0.5, 0.5]}}
    ],
    "sun": {"direction": [0.3, 1, 0.2], "irradiance": [20000, 20000, 20000]},
    "sky": {"type": "gradient", "radiance": [300, 400, 800], "horizon": [600, 600, 600], "ground": [10, 10, 10]},
    "camera": {"position": [0, 3, 5], "target": [0, 0.5, 0], "fov_y_deg": 50}
  })"), "inline");
  for (bool enabled : {true, false}) {
    Settings s = defaults_of("radiance-cache");
    s.width = 40;
    s.height = 24;
    sky_rays(s) = 4;
    rc(s).pre_exposure = enabled;
    std::vector<std::unique_ptr<Pass>> passes;
    passes.push_back(make_visibility_pass());
    passes.push_back(make_gbuffer_pass());
    passes.push_back(make_direct_lighting_pass());
    passes.push_back(std::make_unique<ConstantFinalColor>(2000.0f));
    passes.push_back(make_exposure_pass());
    Executor ex(gpu(), scene, s, std::move(passes), {"exposure", "final_color"});
    for (auto& p : ex.plan().passes) EXPECT_TRUE(p.runs) << p.name << ": " << p.reason;
    ex.run_frame();
    PreExposure gpu0 = read_exposure(ex);
    PreExposure cpu0 = compute_pre_exposure(ex.read("direct_light"), nullptr, 0.0f, enabled);
    ex.run_frame();
    PreExposure gpu1 = read_exposure(ex);
    FloatImage prev = ex.read("final_color");  // the constant, as written last frame
    PreExposure cpu1 = compute_pre_exposure(ex.read("direct_light"), &prev, gpu0.p_now, enabled);
    std::printf("exposure (%s): frame 0 P %.6g (cpu %.6g), average %.6g, lit %u; frame 1 P %.6g (cpu %.6g), "
                "P_prev %.6g, average %.6g, lit %u\n", enabled ? "on" : "off", gpu0.p_now, cpu0.p_now,
                gpu0.average_luminance, gpu0.lit_pixels, gpu1.p_now, cpu1.p_now, gpu1.p_prev,
                gpu1.average_luminance, gpu1.lit_pixels);
    for (auto [g, c] : {std::pair{gpu0, cpu0}, std::pair{gpu1, cpu1}}) {
      EXPECT_NEAR(g.p_now, c.p_now, 1e-4f * c.p_now);
      EXPECT_NEAR(g.p_prev, c.p_prev, 1e-4f * c.p_prev);
      EXPECT_NEAR(g.average_luminance, c.average_luminance, 1e-4f * c.average_luminance);
      EXPECT_EQ(g.lit_pixels, c.lit_pixels);
    }
    if (enabled) {
      // 40x24 read at every 4th pixel per axis: 60 pixels, the sky, sunlit and sky-lit surfaces
      // (a few see neither).
      EXPECT_LE(gpu0.lit_pixels, 60u);
      EXPECT_GT(gpu0.lit_pixels, 54u);
      EXPECT_LT(gpu0.p_now, 1.0f / 300.0f);   // brighter than the dimmest sky
      EXPECT_EQ(gpu0.p_prev, gpu0.p_now);     // first frame
      EXPECT_NE(gpu1.p_now, compute_pre_exposure(ex.read("direct_light"), nullptr, 0.0f).p_now);  // last frame counts
    } else {
      EXPECT_EQ(gpu1.p_now, 1.0f);
      EXPECT_EQ(gpu1.p_prev, 1.0f);
    }
  }
}

}  // namespace
}  // namespace gib
