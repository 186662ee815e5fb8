#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise.h"

#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

namespace gib {
namespace {

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
               {"gi_denoise_tmp_r", Access::write, sh}, {"gi_denoise_tmp_g", Access::write, sh},
               {"gi_denoise_tmp_b", Access::write, sh}, {"gi_sh_r", Access::write, sh},
               {"gi_sh_g", Access::write, sh},          {"gi_sh_b", Access::write, sh},
               {"gather_direct", Access::read},         {"gi_denoise_tmp_direct", Access::write, direct},
               {"gi_direct", Access::write, direct}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    const uint32_t divisor = gather_divisor(r);
    const uint32_t radius = r.denoise_radius;
    const bool tiled = r.denoise_kernel == 0 && radius <= kDenoiseTileMaxRadius;
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
                                              {kDenoiseSpecTileTexels, tiled ? kDenoiseGroup * (kDenoiseGroup + 2 * radius) : 1u}},
                           .scene = false});
      ctx.cmd.end_label();
    };
    run("horizontal", 1, 0, "gather_sh", "gather_direct", "gi_denoise_tmp");
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    run("vertical", 0, 1, "gi_denoise_tmp", "gi_denoise_tmp_direct", "gi_sh");
  }
};

}  // namespace

std::unique_ptr<Pass> make_gi_denoise_pass() { return std::make_unique<GiDenoisePass>(); }

}  // namespace gib
