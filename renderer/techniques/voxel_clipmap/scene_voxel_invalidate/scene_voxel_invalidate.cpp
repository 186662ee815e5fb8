#include "renderer/techniques/voxel_clipmap/scene_voxel_invalidate/scene_voxel_invalidate.h"

#include <vector>

#include "renderer/techniques/voxel_clipmap/scene_voxel_invalidate/scene_voxel_invalidate_shared.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_params.h"

namespace gib {
namespace {

struct Box {
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  void add(Vec3 p) { lo = vmin(lo, p); hi = vmax(hi, p); }
  void add(const Box& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
};

bool same(const Mat4& a, const Mat4& b) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (a.m[i][j] != b.m[i][j]) return false;
  return true;
}

// World boxes of the instances whose transform changed between frame - 1 and frame: each the
// union of its mesh's box under both transforms.
std::vector<Box> moved_boxes(const Scene& scene, uint32_t frame, Vec3 offset) {
  std::vector<Box> boxes;
  if (frame == 0) return boxes;
  const float now = float(frame) * scene.frame_time, before = float(frame - 1) * scene.frame_time;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    if (!inst.changes()) continue;
    const Mat4 a = scene.instance_transform(i, before), b = scene.instance_transform(i, now);
    if (same(a, b)) continue;
    Box box;
    for (const Vec3& p : scene.meshes[inst.mesh].positions) {
      box.add(a.transform_point(p));
      box.add(b.transform_point(p));
    }
    box.lo = {box.lo.x + offset.x, box.lo.y + offset.y, box.lo.z + offset.z};
    box.hi = {box.hi.x + offset.x, box.hi.y + offset.y, box.hi.z + offset.z};
    boxes.push_back(box);
  }
  // Past the push block's room the last boxes merge into one.
  while (boxes.size() > glsl::kScInvalidateMaxBoxes) {
    boxes[boxes.size() - 2].add(boxes.back());
    boxes.pop_back();
  }
  return boxes;
}

class SceneVoxelInvalidatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const VoxelClipmapSettings& p = s.params<VoxelClipmapSettings>();
    PassDecl d;
    d.name = "scene_voxel_invalidate";
    d.needs = Feature::motion;
    d.slots = {{"voxel_clip_state", Access::read_write, vc_state_desc()},
               {"scene_voxel_data", Access::read_write, vc_voxels_desc(p)},
               {"irradiance_cell_state", Access::read_write, vc_cell_state_desc(p)}};
    d.work = {{"voxels", double(vc_voxel_count(p))}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const VoxelClipmapSettings& p = ctx.settings.params<VoxelClipmapSettings>();
    if (!p.invalidate) return;
    const std::vector<Box> boxes = moved_boxes(ctx.scene, ctx.frame, ctx.settings.world_offset);
    if (boxes.empty()) return;
    ScInvalidatePush push{};
    push.vc = make_vc_params(ctx.scene, ctx.settings, ctx.frame);
    for (size_t i = 0; i < boxes.size(); ++i) {
      push.box_min[i] = {boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z, 0};
      push.box_max[i] = {boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z, 0};
    }
    const std::vector<BufferBinding> buffers{{kScInvalidateBindState, "voxel_clip_state"},
                                             {kScInvalidateBindVoxels, "scene_voxel_data"},
                                             {kScInvalidateBindCells, "irradiance_cell_state"}};
    for (uint32_t target : {1u, 2u}) {
      push.count = {uint32_t(boxes.size()), target, 0, 0};
      const uint32_t items = uint32_t(target == 1 ? vc_voxel_count(p) : vc_cell_count(p));
      record_compute(ctx, {.shader = "scene_voxel_invalidate.comp",
                           .groups_x = div_up(items, kScInvalidateGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .buffers = buffers,
                           .label = target == 1 ? "scene_voxel_invalidate/voxels" : "scene_voxel_invalidate/cells",
                           .barrier_after = true});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_scene_voxel_invalidate_pass() { return std::make_unique<SceneVoxelInvalidatePass>(); }

}  // namespace gib
