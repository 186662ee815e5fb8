#include "renderer/techniques/deferred/material_classify/material_classify.h"

#include <algorithm>

#include "renderer/techniques/deferred/deferred.h"
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"

namespace gib {
namespace {

uint32_t material_count(const Scene& scene) { return std::max<uint32_t>(1, uint32_t(scene.materials.size())); }

class MaterialClassifyPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    const uint32_t m = material_count(scene);
    PassDecl d;
    d.name = "material_classify";
    d.slots = {{"vbuffer", Access::read},
               {"material_segments", Access::write,
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, material_segment_words(s.width, s.height, m) * 4}},
               {"pixel_commands", Access::write,
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, material_command_capacity(s.width, s.height, m) * 4}}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const uint32_t w = ctx.width("vbuffer"), h = ctx.height("vbuffer");
    MatClassifyPush push{material_count(ctx.scene), div_up(w, kDeferredTile), deferred_tiles(w, h), 0};
    static_assert(sizeof(push) == 16, "MatClassifyPush must match the material_classify kernels");
    ctx.cmd.fill(ctx.buffer("material_segments"), 0u);
    ctx.cmd.fill(ctx.buffer("pixel_commands"), kDeferredPixelPad);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const std::vector<BufferBinding> buffers = {{kMatBindSegments, "material_segments"}, {kMatBindCommands, "pixel_commands"}};
    record_compute(ctx, {.shader = "material_classify_count.comp",
                         .images = {{kMatBindVbuffer, "vbuffer"}},
                         .groups_x = div_up(w, kMatClassifyGroup),
                         .groups_y = div_up(h, kMatClassifyGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    record_compute(ctx, {.shader = "material_classify_scan.comp",
                         .images = {{kMatBindVbuffer, "vbuffer"}},
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    record_compute(ctx, {.shader = "material_classify_write.comp",
                         .images = {{kMatBindVbuffer, "vbuffer"}},
                         .groups_x = push.tiles,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
  }
};

}  // namespace

uint64_t material_segment_words(uint32_t width, uint32_t height, uint32_t materials) {
  return glsl::kSegHeader + 2ull * deferred_tiles(width, height) * materials;
}

uint64_t material_command_capacity(uint32_t width, uint32_t height, uint32_t materials) {
  const uint64_t pixels = uint64_t(width) * height;
  const uint64_t segments = std::min<uint64_t>(uint64_t(deferred_tiles(width, height)) * materials, pixels);
  return pixels + segments * (glsl::kDeferredWave - 1);
}

std::unique_ptr<Pass> make_material_classify_pass() { return std::make_unique<MaterialClassifyPass>(); }

}  // namespace gib
