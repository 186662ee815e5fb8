#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise.h"

#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {
namespace {

enum class Layout { fused, tiled, per_tap };

// denoise_kernel 0: both directions in one dispatch where the radius fits the fused tile, else
// two tiled dispatches where it fits theirs, else per tap; 1 per tap; 2 two tiled dispatches.
Layout denoise_layout(const RadianceCacheSettings& r) {
  if (r.denoise_kernel == 1 || r.denoise_radius > glsl::kDenoiseTileMaxRadius) return Layout::per_tap;
  if (r.denoise_kernel == 0 && r.denoise_radius <= glsl::kDenoiseFusedMaxRadius) return Layout::fused;
  return Layout::tiled;
}

class GiDenoisePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const SizeRule size = gather_size_rule(s.params<RadianceCacheSettings>());
    const ResourceDesc sh =  // x L0, yzw L1
        ResourceDesc{Format::rgba16_float, size}.with(non_negative_values().allow_negative(kChannelG | kChannelB | kChannelA));
    const ResourceDesc direct = ResourceDesc{Format::rgba16_float, size}.with(non_negative_values());
    PassDecl d;
    d.name = "gi_denoise";
    d.slots = {{"gather_sh_r", Access::read},      {"gather_sh_g", Access::read},
               {"gather_sh_b", Access::read},      {"gather_hit_distance", Access::read},
               {"gbuffer_normal", Access::read},   {"gbuffer_position", Access::read},
               {"gi_sh_r", Access::write, sh},     {"gi_sh_g", Access::write, sh},
               {"gi_sh_b", Access::write, sh},     {"gather_direct", Access::read},
               {"gi_direct", Access::write, direct}};
    // The horizontal direction's output, when it goes through images (the fused kernel keeps it
    // in group-shared memory).
    if (denoise_layout(s.params<RadianceCacheSettings>()) != Layout::fused)
      for (const char* c : {"r", "g", "b"}) d.slots.push_back({std::string("gi_denoise_tmp_") + c, Access::write, sh});
    if (denoise_layout(s.params<RadianceCacheSettings>()) != Layout::fused)
      d.slots.push_back({"gi_denoise_tmp_direct", Access::write, direct});
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    const uint32_t divisor = gather_divisor(r);
    const uint32_t radius = r.denoise_radius;
    const Layout layout = denoise_layout(r);
    const bool tiled = layout != Layout::per_tap, fused = layout == Layout::fused;
    const uint32_t tile_texels = fused ? (kDenoiseGroup + 2 * radius) * (kDenoiseGroup + 2 * radius)
                                       : kDenoiseGroup * (kDenoiseGroup + 2 * radius);
    auto run = [&](const char* label, int ax, int ay, const char* in, const char* in_direct, const char* out) {
      const std::string ir = std::string(in) + "_r", ig = std::string(in) + "_g", ib = std::string(in) + "_b";
      const std::string o_r = std::string(out) + "_r", og = std::string(out) + "_g", ob = std::string(out) + "_b";
      const std::string id = std::string(in_direct), od = std::string(out) == "gi_sh" ? "gi_direct" : std::string(out) + "_direct";
      DenoisePush push{ax, ay, radius, divisor, ctx.settings.nan_guards ? 1u : 0u, r.denoise_hit_weight ? 1u : 0u, 0, 0};
      static_assert(sizeof(push) == 32, "DenoisePush must match gi_denoise.comp's push block");
      ctx.cmd.begin_label(std::string("gi_denoise/") + label);
      record_compute(ctx, {.shader = "gi_denoise.comp",
                           .images = {{kDenoiseBindNormal, "gbuffer_normal"},
                                      {kDenoiseBindPosition, "gbuffer_position"},
                                      {kDenoiseBindHit, "gather_hit_distance"},
                                      {kDenoiseBindInR, ir.c_str()},
                                      {kDenoiseBindInG, ig.c_str()},
                                      {kDenoiseBindInB, ib.c_str()},
                                      {kDenoiseBindOutR, o_r.c_str()},
                                      {kDenoiseBindOutG, og.c_str()},
                                      {kDenoiseBindOutB, ob.c_str()},
                                      {kDenoiseBindInDirect, id.c_str()},
                                      {kDenoiseBindOutDirect, od.c_str()}},
                           .groups_x = div_up(ctx.width("gi_sh_r"), kDenoiseGroup),
                           .groups_y = div_up(ctx.height("gi_sh_r"), kDenoiseGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kDenoiseSpecTiled, tiled ? 1u : 0u},
                                              {kDenoiseSpecTileTexels, tiled ? tile_texels : 1u},
                                              {kDenoiseSpecFused, fused ? 1u : 0u}},
                           .scene = false});
      ctx.cmd.end_label();
    };
    if (fused) {
      run("fused", 1, 0, "gather_sh", "gather_direct", "gi_sh");
      return;
    }
    run("horizontal", 1, 0, "gather_sh", "gather_direct", "gi_denoise_tmp");
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    run("vertical", 0, 1, "gi_denoise_tmp", "gi_denoise_tmp_direct", "gi_sh");
  }
};

}  // namespace

std::unique_ptr<Pass> make_gi_denoise_pass() { return std::make_unique<GiDenoisePass>(); }

}  // namespace gib
