#include "renderer/passes/shadow_minmax/shadow_minmax.h"

#include <algorithm>
#include <utility>

#include "renderer/passes/shadow_cascades.h"
#include "renderer/passes/shadow_minmax/shadow_minmax_shared.h"

namespace gib {
namespace {

class ShadowMinMaxPass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const auto& g = s.params<SunShadowParams>();
    const uint32_t tiles = shadow_map_resolution(g) / glsl::kShadowMinMaxTile;
    const uint32_t n = std::clamp<uint32_t>(g.shadow_cascades, 1, glsl::kShadowMaxCascades);
    ResourceDesc mm = ResourceDesc{Format::rg32_float, SizeRule::fixed, tiles * n, tiles}.with(unit_values());
    PassDecl d;
    d.name = "shadow_minmax";
    d.needs = Feature::sun;
    d.slots = {{"shadow_map", Access::read},
               {"shadow_minmax_tiles", Access::write, mm},
               {"shadow_minmax_rows", Access::write, mm},
               {"shadow_minmax", Access::write, mm}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    glsl::ShadowCascadePush push = shadow_cascade_push(ctx.settings.params<SunShadowParams>(), ctx.scene.camera.near_plane);
    const uint32_t w = ctx.width("shadow_minmax"), h = ctx.height("shadow_minmax");
    record_compute(ctx, {.shader = "shadow_minmax_tiles.comp",
                         .images = {{kShadowBindMap, "shadow_map"}, {kMinMaxBindTiles, "shadow_minmax_tiles"}},
                         .groups_x = div_up(w, kShadowGroup),
                         .groups_y = div_up(h, kShadowGroup),
                         .scene = false});
    // Dilate along x into shadow_minmax_rows, then along y into shadow_minmax.
    const std::pair<const char*, const char*> steps[2] = {{"shadow_minmax_tiles", "shadow_minmax_rows"},
                                                          {"shadow_minmax_rows", "shadow_minmax"}};
    for (int axis = 0; axis < 2; ++axis) {
      push.counts.z = axis == 0 ? 1u : 0u;  // the dilation axis: 1 x, 0 y
      ctx.cmd.barrier(kStageCompute, kStageCompute);
      record_compute(ctx, {.shader = "shadow_minmax.comp",
                           .images = {{kMinMaxBindTiles, steps[axis].first}, {kShadowBindMinMax, steps[axis].second}},
                           .groups_x = div_up(w, kShadowGroup),
                           .groups_y = div_up(h, kShadowGroup),
                           .push = &push,
                           .push_bytes = sizeof(push)});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_shadow_minmax_pass() { return std::make_unique<ShadowMinMaxPass>(); }

}  // namespace gib
