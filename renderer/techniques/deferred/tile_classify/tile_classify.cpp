#include "renderer/techniques/deferred/tile_classify/tile_classify.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/tile_classify/tile_classify_shared.h"

namespace gib {
namespace {

class TileClassifyPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "tile_classify";
    d.slots = {{"gbuffer_position", Access::read},
               {"gbuffer_emissive", Access::read},
               {"vbuffer", Access::read},
               {"gbuffer_normal", Access::read},
               {"tile_workloads", Access::write,
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, tile_workload_words(s.width, s.height) * 4}}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const uint32_t w = ctx.width("gbuffer_position"), h = ctx.height("gbuffer_position");
    TilePush push{div_up(w, kDeferredTile), deferred_tiles(w, h), 0, 0};
    static_assert(sizeof(push) == 16, "TilePush must match the tile_classify kernels");
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.fill(ctx.buffer("tile_workloads"), 0u);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const DeviceInfo& dev = ctx.gpu.info();
    const std::vector<ImageBinding> images = {{kTileBindPosition, "gbuffer_position"},
                                              {kTileBindEmissive, "gbuffer_emissive"},
                                              {kTileBindVbuffer, "vbuffer"},
                                              {kTileBindNormal, "gbuffer_normal"}};
    const std::vector<BufferBinding> buffers = {{kTileBindWorkloads, "tile_workloads"}};
    const bool scalarised = dev.subgroup_vote && dev.subgroup_ballot && dev.subgroup_arithmetic;
    record_compute(ctx, {.shader = scalarised ? "tile_classify_mask.comp" : "tile_classify_mask_plain.comp",
                         .images = images,
                         .groups_x = div_up(w, kTileMaskGroup),
                         .groups_y = div_up(h, kTileMaskGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    record_compute(ctx, {.shader = "tile_classify_args.comp",
                         .images = images,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
  }
};

}  // namespace

uint64_t tile_workload_words(uint32_t width, uint32_t height) {
  return glsl::kTileHeader + uint64_t(glsl::kTileListCount + 1) * deferred_tiles(width, height);
}

std::unique_ptr<Pass> make_tile_classify_pass() { return std::make_unique<TileClassifyPass>(); }

}  // namespace gib
