#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.h"

#include <fmt/format.h>

#include <cmath>

#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {

Format gi_history_format(uint32_t history_format) {
  switch (history_format) {
    case 0: return Format::r32_uint;  // RGB9E5, packed in the shader
    case 1: return Format::rgba16_float;
    case 2: return Format::b10g11r11_float;
    case 3: return Format::rgba32_float;
  }
  throw GraphError(fmt::format("gi_upscale: history_format expected 0 (rgb9e5), 1 (rgba16f), 2 (r11g11b10f) "
                               "or 3 (rgba32f), got {}", history_format));
}

std::string gi_history_shader(const std::string& stem, uint32_t history_format) {
  static const char* const kSuffixes[] = {"_rgb9e5.comp", "_rgba16f.comp", "_r11g11b10f.comp", "_rgba32f.comp"};
  (void)gi_history_format(history_format);  // throws when out of range
  return stem + kSuffixes[history_format];
}

namespace {

// The side of the gather-pixel tile an 8x8 group of full-res pixels reads (gi_upscale.glsl,
// load_gather_tile): from one before the first bilinear tap of its first pixel to two after
// that of its last (the 4x4 fallback). Groups start at multiples of 8, which every divisor
// divides, so the first group's extent is every group's: 11, 8 and 6 at divisors 1, 2 and 4
// (121 x 56 B = 6.6 KB at most).
uint32_t upscale_tile_side(uint32_t divisor) {
  auto first_tap = [&](int p) {  // floor((p - divisor / 2) / divisor), as the shader
    return int(std::floor((float(p) - float(divisor / 2)) / float(divisor)));
  };
  return uint32_t((first_tap(glsl::kUpscaleGroup - 1) + 2) - (first_tap(0) - 1) + 1);
}

class GiUpscalePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
    ResourceDesc history{gi_history_format(r.history_format), SizeRule::render};
    ResourceDesc frames{Format::r32_float, SizeRule::render};
    history.persistent = frames.persistent = true;
    history.values = non_negative_values().only(kChannelsRgb).encoded(  // irradiance / pi
        history.format == Format::r32_uint ? Encoding::rgb9e5 : Encoding::none);
    frames.values = non_negative_values().bounded(float(r.history_max_frames));  // n of the temporal filter
    PassDecl d;
    d.name = "gi_upscale";
    d.slots = {{"gi_sh_r", Access::read},
               {"gi_sh_g", Access::read},
               {"gi_sh_b", Access::read},
               {"gbuffer_normal", Access::read},
               {"gbuffer_position", Access::read},
               {"gbuffer_normal", Access::read_prev},
               {"gbuffer_position", Access::read_prev},
               {"gi_direct", Access::read},
               {"gi_history", Access::write, history},
               {"gi_history", Access::read_prev},
               {"gi_history_direct", Access::write, history},
               {"gi_history_direct", Access::read_prev},
               {"gi_history_frames", Access::write, frames},
               {"gi_history_frames", Access::read_prev},
               {"exposure", Access::read}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    UpscalePush push{gather_divisor(r), float(r.history_max_frames), r.disocclusion ? 1u : 0u,
                     ctx.frame > 0 ? 1u : 0u, ctx.settings.nan_guards ? 1u : 0u, r.dither_stores ? 1u : 0u,
                     ctx.frame, 0};
    static_assert(sizeof(push) == 32, "UpscalePush must match gi_upscale.glsl's push block");
    ComputePipelineDesc desc;
    desc.shader = gi_history_shader("gi_upscale", r.history_format);
    desc.bindings = scene_bindings();
    desc.push_constant_bytes = sizeof(push);
    const bool tiled = r.upscale_kernel == 0;
    desc.spec_constants = {{kUpscaleSpecTiled, tiled ? 1u : 0u},
                           {kUpscaleSpecTileSide, tiled ? upscale_tile_side(push.divisor) : 1u}};
    std::vector<Bind> binds = ctx.scene_gpu.binds();
    auto image = [&](uint32_t binding, const Image& img) {
      desc.bindings.push_back({binding, DescriptorKind::storage_image});
      binds.push_back({binding, nullptr, &img});
    };
    image(kUpscaleBindNormal, ctx.image("gbuffer_normal"));
    image(kUpscaleBindPosition, ctx.image("gbuffer_position"));
    image(kUpscaleBindPrevNormal, ctx.prev_image("gbuffer_normal"));
    image(kUpscaleBindPrevPosition, ctx.prev_image("gbuffer_position"));
    image(kUpscaleBindShR, ctx.image("gi_sh_r"));
    image(kUpscaleBindShG, ctx.image("gi_sh_g"));
    image(kUpscaleBindShB, ctx.image("gi_sh_b"));
    image(kUpscaleBindPrevHistory, ctx.prev_image("gi_history"));
    image(kUpscaleBindPrevFrames, ctx.prev_image("gi_history_frames"));
    image(kUpscaleBindHistory, ctx.image("gi_history"));
    image(kUpscaleBindFrames, ctx.image("gi_history_frames"));
    image(kUpscaleBindDirect, ctx.image("gi_direct"));
    image(kUpscaleBindPrevHistoryDirect, ctx.prev_image("gi_history_direct"));
    image(kUpscaleBindHistoryDirect, ctx.image("gi_history_direct"));
    desc.bindings.push_back({kUpscaleBindExposure, DescriptorKind::storage_buffer});
    binds.push_back({kUpscaleBindExposure, &ctx.buffer("exposure"), nullptr});
    auto pipeline = ctx.gpu.compute_pipeline(desc);
    ctx.cmd.bind(*pipeline, binds, &push, sizeof(push));
    ctx.cmd.dispatch(div_up(ctx.width("gi_history"), kUpscaleGroup),
                     div_up(ctx.height("gi_history"), kUpscaleGroup));
  }
};

}  // namespace

std::unique_ptr<Pass> make_gi_upscale_pass() { return std::make_unique<GiUpscalePass>(); }

}  // namespace gib
