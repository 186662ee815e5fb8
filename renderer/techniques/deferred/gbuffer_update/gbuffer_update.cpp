#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.h"

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update_shared.h"

namespace gib {
namespace {

class GbufferUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "gbuffer_update";
    d.needs = Feature::decals;
    const DeferredSettings& ds = s.params<DeferredSettings>();
    d.slots = {{"vbuffer", Access::read}, {"gbuffer_position", Access::read}, {"gbuffer_normal", Access::read}};
    // gbuffer_update 0 (a negative control) leaves the pass without an output: the graph culls it.
    if (ds.gbuffer_update) d.slots.push_back({"gbuffer_albedo", Access::read_write});
    if (ds.tile_classification) d.slots.push_back({"tile_workloads", Access::read});
    if (ds.vrcs && ds.tile_classification) d.slots.push_back({"vrcs_rates", Access::read_write});
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeferredSettings& ds = ctx.settings.params<DeferredSettings>();
    const uint32_t w = ctx.width("gbuffer_albedo"), h = ctx.height("gbuffer_albedo");
    const uint32_t tiles_x = div_up(w, kDeferredTile);
    UpdatePush push{tiles_x, tiles_x * div_up(h, kDeferredTile), div_up(w, kVrcsTile), 0};
    static_assert(sizeof(push) == 16, "UpdatePush must match gbuffer_update.glsl's push block");
    static_assert(kUpdateGroup == kLightingGroup, "gbuffer_update covers listed tiles as the lighting does (tile_list.glsl)");
    const std::vector<ImageBinding> images = {{kUpdateBindVbuffer, "vbuffer"},
                                              {kUpdateBindPosition, "gbuffer_position"},
                                              {kUpdateBindNormal, "gbuffer_normal"},
                                              {kUpdateBindAlbedo, "gbuffer_albedo"}};
    if (!ds.tile_classification) {
      record_compute(ctx, {.shader = "gbuffer_update_uber.comp",
                           .images = images,
                           .groups_x = div_up(w, kUpdateGroup),
                           .groups_y = div_up(h, kUpdateGroup),
                           .push = &push,
                           .push_bytes = sizeof(push)});
      return;
    }
    std::vector<BufferBinding> buffers = {{kUpdateBindWorkloads, "tile_workloads"}};
    if (ds.vrcs) buffers.push_back({kUpdateBindRates, "vrcs_rates"});
    record_compute(ctx, {.shader = !ds.vrcs ? "gbuffer_update.comp"
                                  : ctx.gpu.info().subgroup_arithmetic ? "gbuffer_update_vrcs.comp"
                                                                       : "gbuffer_update_vrcs_plain.comp",
                         .images = images,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers,
                         .indirect = "tile_workloads",
                         .indirect_offset = 16ull * kTileListDecals});
  }
};

}  // namespace

std::unique_ptr<Pass> make_gbuffer_update_pass() { return std::make_unique<GbufferUpdatePass>(); }

}  // namespace gib
