#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing_shared.h"

namespace gib {
namespace {

class DeferredTexturingPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    PassDecl d;
    d.name = "deferred_texturing";
    ResourceDesc normal{Format::rgba16_float, SizeRule::render}, position{Format::rgba32_float, SizeRule::render};
    normal.persistent = position.persistent = true;
    normal.values = unit_values().allow_negative(kChannelsRgb);
    position.values = non_negative_values().allow_negative(kChannelsRgb);
    d.slots = {{"vbuffer", Access::read},
               {"vis_bary", Access::read},
               {"vis_bary_deriv", Access::read},
               {"vis_tangent_frame", Access::read},
               {"gbuffer_albedo", Access::write, ResourceDesc{Format::rgba16_float, SizeRule::render}.with(unit_values())},
               {"gbuffer_normal", Access::write, normal},
               {"gbuffer_position", Access::write, position},
               {"gbuffer_emissive", Access::write, ResourceDesc{Format::rgba16_float, SizeRule::render}.with(non_negative_values())}};
    const DeferredSettings& ds = s.params<DeferredSettings>();
    if (ds.classify_materials)
      d.slots.insert(d.slots.end(), {{"material_segments", Access::read_write}, {"pixel_commands", Access::read}});
    if (ds.classify_materials && ds.vrcs) d.slots.push_back({"vrcs_rates", Access::read_write});
    (void)scene;
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeferredSettings& ds = ctx.settings.params<DeferredSettings>();
    const DebugSettings& dbg = ctx.settings.debug;
    const uint32_t w = ctx.width("vbuffer"), h = ctx.height("vbuffer");
    TexPush push{div_up(w, kDeferredTile), ctx.settings.nan_guards ? 1u : 0u, dbg.injects(1, ctx.frame) ? 1u : 0u,
                 dbg.inject_x, dbg.inject_y, div_up(w, kVrcsTile), 0, 0};
    static_assert(sizeof(push) == 32, "TexPush must match deferred_texturing.glsl's push block");
    std::vector<ImageBinding> images = {{kTexBindVbuffer, "vbuffer"},          {kTexBindBary, "vis_bary"},
                                        {kTexBindBaryDeriv, "vis_bary_deriv"}, {kTexBindTangentFrame, "vis_tangent_frame"},
                                        {kTexBindAlbedo, "gbuffer_albedo"},    {kTexBindNormal, "gbuffer_normal"},
                                        {kTexBindPosition, "gbuffer_position"}, {kTexBindEmissive, "gbuffer_emissive"}};
    // The uber kernel (every pixel), or the sky kernel: sky pixels are in no list, and it writes
    // them zero as the uber kernel does. Both run over 8x8-pixel workgroups.
    record_compute(ctx, {.shader = ds.classify_materials ? "deferred_texturing_sky.comp" : "deferred_texturing_uber.comp",
                         .images = images,
                         .groups_x = div_up(w, 8),
                         .groups_y = div_up(h, 8),
                         .push = &push,
                         .push_bytes = sizeof(push)});
    if (!ds.classify_materials) return;
    const DeviceInfo& dev = ctx.gpu.info();
    const bool subgroups = dev.subgroup_vote && dev.subgroup_ballot && dev.subgroup_arithmetic;
    const bool uniform = subgroups && ds.uniform_permutation;
    std::vector<uint32_t> perms;
    if (uniform) perms.push_back(kTexPermUniform);
    perms.push_back(subgroups ? kTexPermDivergent : kTexPermPlain);
    std::string kernel = subgroups ? "deferred_texturing" : "deferred_texturing_plain";
    std::vector<BufferBinding> buffers = {{kTexBindSegments, "material_segments"}, {kTexBindCommands, "pixel_commands"}};
    if (ds.vrcs) {
      kernel += "_vrcs";
      buffers.push_back({kTexBindRates, "vrcs_rates"});
    }
    for (uint32_t shader = 0; shader < kDeferredShaderCount; ++shader)
      for (uint32_t perm : perms)
        record_compute(ctx, {.shader = kernel + ".comp",
                             .images = images,
                             .push = &push,
                             .push_bytes = sizeof(push),
                             .spec_constants = {{kTexSpecShader, shader},
                                                {kTexSpecPermutation, perm},
                                                {kTexSpecHasUniform, uniform ? 1u : 0u}},
                             .buffers = buffers,
                             .indirect = "material_segments",
                             .indirect_offset = 16ull * shader});
  }
};

}  // namespace

std::unique_ptr<Pass> make_deferred_texturing_pass() { return std::make_unique<DeferredTexturingPass>(); }

}  // namespace gib
