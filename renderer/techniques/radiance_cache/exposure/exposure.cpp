#include "renderer/techniques/radiance_cache/exposure/exposure.h"

#include <algorithm>
#include <cmath>

#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {
namespace {

double luminance(const FloatImage& img, size_t i) {
  const float* c = &img.pixels[i * img.channels];
  const float y = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
  return std::isfinite(y) && y > 0.0f ? double(y) : 0.0;
}

class ExposurePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    ResourceDesc buf{Format::buffer, SizeRule::buffer};
    buf.bytes = glsl::kExposureWords * sizeof(float);
    buf.persistent = true;
    // P_now and P_prev (words 0 and 1 of the single element).
    buf.values = non_negative_values()
                     .bounded(std::ldexp(1.0f, int(glsl::kExposureMaxLog2)))
                     .layout(glsl::kExposureWords, glsl::kExposureNow, 2);
    PassDecl d;
    d.name = "exposure";
    d.slots = {{"direct_light", Access::read},
               {"final_color", Access::read_prev},
               {"exposure", Access::read_write, buf}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    static_assert(kExposureWords == kExposurePartialFirst + 2 * kExposurePartials, "exposure buffer layout");
    const uint64_t pixels = uint64_t((ctx.settings.width + kExposureStride - 1) / kExposureStride) *
                            ((ctx.settings.height + kExposureStride - 1) / kExposureStride);
    const uint32_t partials =
        uint32_t(std::clamp<uint64_t>((pixels + kExposureGroup - 1) / kExposureGroup, 1, kExposurePartials));
    for (uint32_t stage = 0; stage < 2; ++stage) {
      ExposurePush push{ctx.settings.params<RadianceCacheSettings>().pre_exposure ? 1u : 0u, ctx.frame > 0 ? 1u : 0u, stage, partials};
      static_assert(sizeof(push) == 16, "ExposurePush must match exposure.comp's push block");
      if (stage == 1) ctx.cmd.barrier(kStageCompute, kStageCompute);
      record_compute(ctx, {.shader = "exposure.comp",
                           .images = {{kExposureBindDirect, "direct_light"},
                                      {kExposureBindPrevColor, "final_color", true}},
                           .groups_x = stage == 0 ? partials : 1,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .scene = false,
                           .buffers = {{kExposureBindOut, "exposure"}}});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_exposure_pass() { return std::make_unique<ExposurePass>(); }

PreExposure compute_pre_exposure(const FloatImage& direct, const FloatImage* prev_color, float stored_p_now,
                                 bool enabled) {
  PreExposure r;
  double sum = 0.0;
  if (enabled)
    for (uint32_t py = 0; py < direct.height; py += glsl::kExposureStride)
      for (uint32_t px = 0; px < direct.width; px += glsl::kExposureStride) {
        const size_t i = size_t(py) * direct.width + px;
        double y = luminance(direct, i);
        if (prev_color) y = std::max(y, luminance(*prev_color, i));
        if (y > double(glsl::kExposureMinLuminance)) {
          sum += std::log2(y);
          ++r.lit_pixels;
        }
      }
  if (r.lit_pixels > 0) {
    const double mean = sum / double(r.lit_pixels);
    r.average_luminance = float(std::exp2(mean));
    r.p_now = float(std::exp2(std::clamp(-mean, -double(glsl::kExposureMaxLog2), double(glsl::kExposureMaxLog2))));
  }
  r.p_prev = prev_color ? stored_p_now : r.p_now;
  return r;
}

}  // namespace gib
