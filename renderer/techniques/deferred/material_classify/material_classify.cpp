#include "renderer/techniques/deferred/material_classify/material_classify.h"

#include <algorithm>
#include <utility>

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
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, material_command_capacity(s.width, s.height, m) * 4}},
               {"material_scan_blocks", Access::write,
                ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0,
                             4ull * glsl::kMatBlockWords * glsl::kDeferredShaderCount *
                                 material_scan_blocks(s.width, s.height, m)}}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const uint32_t w = ctx.width("vbuffer"), h = ctx.height("vbuffer");
    const uint32_t m = material_count(ctx.scene);
    MatClassifyPush push{m, div_up(w, kDeferredTile), deferred_tiles(w, h), material_scan_blocks(w, h, m)};
    static_assert(sizeof(push) == 16, "MatClassifyPush must match the material_classify kernels");
    ctx.cmd.fill(ctx.buffer("material_segments"), 0u);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    const std::vector<BufferBinding> buffers = {{kMatBindSegments, "material_segments"}, {kMatBindCommands, "pixel_commands"}};
    const std::vector<BufferBinding> scan_buffers = {{kMatBindSegments, "material_segments"},
                                                     {kMatBindBlocks, "material_scan_blocks"}};
    record_compute(ctx, {.shader = "material_classify_count.comp",
                         .images = {{kMatBindVbuffer, "vbuffer"}},
                         .groups_x = push.tiles,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .buffers = buffers});
    ctx.cmd.barrier(kStageCompute, kStageCompute);
    // The prefix scan in three steps: per-block sums (a workgroup per block), one workgroup over
    // the blocks' sums, then each block's offsets (a workgroup per block).
    const std::pair<const char*, uint32_t> steps[] = {{"material_classify_blocks.comp", push.blocks},
                                                      {"material_classify_scan.comp", 1u},
                                                      {"material_classify_offsets.comp", push.blocks}};
    for (const auto& [shader, groups] : steps) {
      record_compute(ctx, {.shader = shader,
                           .images = {{kMatBindVbuffer, "vbuffer"}},
                           .groups_x = groups,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .buffers = scan_buffers});
      ctx.cmd.barrier(kStageCompute, kStageCompute);
    }
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

uint32_t material_scan_blocks(uint32_t width, uint32_t height, uint32_t materials) {
  const uint64_t entries = uint64_t(deferred_tiles(width, height)) * materials;
  return uint32_t(std::max<uint64_t>(1, (entries + glsl::kMatScanSize - 1) / glsl::kMatScanSize));
}

void material_scan_cpu(std::vector<uint32_t>& seg, uint32_t tiles, const std::vector<uint32_t>& shader_of_material) {
  using namespace glsl;
  const uint32_t m = uint32_t(shader_of_material.size());
  const uint64_t entries = uint64_t(tiles) * m;
  uint32_t slot = 0, pixels = 0, segments = 0;
  for (uint64_t e = 0; e < entries; ++e) seg[kSegHeader + entries + e] = 0;
  for (uint32_t s = 0; s < kDeferredShaderCount; ++s) {
    const uint32_t first = slot;
    for (uint64_t e = 0; e < entries; ++e) {
      const uint32_t count = std::min(shader_of_material[e % m], kDeferredShaderCount - 1) == s ? seg[kSegHeader + e] : 0;
      if (count == 0) continue;
      seg[kSegHeader + entries + e] = slot;
      slot += (count + kDeferredWave - 1) / kDeferredWave * kDeferredWave;
      pixels += count;
      ++segments;
    }
    seg[4 * s + 0] = (slot - first) / kDeferredWave;
    seg[4 * s + 1] = 1;
    seg[4 * s + 2] = 1;
    seg[4 * s + 3] = first / kDeferredWave;
  }
  seg[kSegStats + kStatPixels] = pixels;
  seg[kSegStats + kStatWaves] = slot / kDeferredWave;
  seg[kSegStats + kStatPaddingSlots] = slot - pixels;
  seg[kSegStats + kStatSegments] = segments;
}

std::unique_ptr<Pass> make_material_classify_pass() { return std::make_unique<MaterialClassifyPass>(); }

}  // namespace gib
