// The pass interface: a pass declares its slots (pure, no GPU) and records its dispatches
// against the resources the graph allocated for exactly those slots.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"
#include "renderer/graph/settings.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/gpu.h"

namespace gib {

static_assert(kStageCompute == 1u << static_cast<uint32_t>(PassKind::compute) &&
                  kStageGraphics == 1u << static_cast<uint32_t>(PassKind::graphics) &&
                  kStageTransfer == 1u << static_cast<uint32_t>(PassKind::transfer),
              "the Vulkan layer's stage bits are the graph's 1 << PassKind");

// The scene as GPU buffers, in the binding order of frame_shared.h / scene.glsl.
struct SceneGpu {
  std::shared_ptr<Buffer> frame;  // GpuFrame (uniform)
  std::array<std::shared_ptr<Buffer>, 7> buffers;
  std::shared_ptr<Buffer> textures;  // packed image textures (kBindSceneTextures), static
  uint32_t triangle_count = 0;
  uint32_t instance_count = 0;
  uint32_t light_count = 0;
  // Binds for frame + scene buffers (bindings 0..7) and the textures (kBindSceneTextures).
  std::vector<Bind> binds() const;
};

struct ResolvedSlot {
  const ResolvedResource* resource = nullptr;
  Access access = Access::read;
  std::shared_ptr<Image> image, prev_image;  // prev_image: last frame's copy (read_prev)
  std::shared_ptr<Buffer> buffer, prev_buffer;
};

class RecordContext {
 public:
  RecordContext(Gpu& gpu, Cmd& cmd, const Scene& scene, const SceneGpu& scene_gpu, const Settings& settings,
                uint32_t frame, std::string pass, std::map<std::string, ResolvedSlot> slots)
      : gpu(gpu), cmd(cmd), scene(scene), scene_gpu(scene_gpu), settings(settings), frame(frame),
        pass_(std::move(pass)), slots_(std::move(slots)) {}
  Gpu& gpu;
  Cmd& cmd;
  const Scene& scene;
  const SceneGpu& scene_gpu;
  const Settings& settings;
  const uint32_t frame;

  // Touching a resource the pass did not declare throws GraphError.
  const Image& image(const std::string& name) const;
  const Image& prev_image(const std::string& name) const;
  const Buffer& buffer(const std::string& name) const;
  const Buffer& prev_buffer(const std::string& name) const;
  uint32_t width(const std::string& name) const { return image(name).width(); }
  uint32_t height(const std::string& name) const { return image(name).height(); }

 private:
  const ResolvedSlot& slot(const std::string& name) const;
  std::string pass_;
  std::map<std::string, ResolvedSlot> slots_;
};

class Pass {
 public:
  virtual ~Pass() = default;
  virtual PassDecl declare(const Scene& scene, const Settings& settings) const = 0;
  virtual void record(RecordContext& ctx) = 0;
};

// Descriptor layout of the scene bundle (frame uniform at 0, scene buffers at 1..7, the packed
// textures at 31, kBindSceneTextures); a pass appends its own slots from binding 8
// (kBindPassFirst) and stays below 31.
std::vector<BindingDecl> scene_bindings();

// The common shape of a compute pass: the scene bundle plus storage images bound by slot name,
// one dispatch. Push constants and specialization constants optional.
// prev: bind last frame's copy of a ping-pong resource (the slot declares read_prev).
// sampled: bind it as a combined image sampler (nearest, clamp to edge: the Vulkan layer's one
// sampler) instead of a storage image, for texelFetch and textureGather (four texels a load).
struct ImageBinding {
  uint32_t binding;
  const char* slot;
  bool prev = false;
  bool sampled = false;
};
struct BufferBinding {  // a storage buffer slot
  uint32_t binding;
  const char* slot;
  bool prev = false;
};
struct ComputeDispatch {
  std::string shader;
  std::vector<ImageBinding> images;
  uint32_t groups_x = 1, groups_y = 1, groups_z = 1;
  const void* push = nullptr;
  uint32_t push_bytes = 0;
  std::vector<SpecConstant> spec_constants;
  bool scene = true;  // bind frame + scene buffers
  std::vector<BufferBinding> buffers;
  const char* indirect = nullptr;  // buffer slot holding VkDispatchIndirectCommand: replaces groups_*
  uint64_t indirect_offset = 0;
  const char* label = nullptr;  // debug label around the dispatch (a pass's sub-dispatch: "pass/step")
  bool barrier_after = false;   // compute -> compute barrier after it (the next dispatch reads its writes)
};
void record_compute(RecordContext& ctx, const ComputeDispatch& d);

inline uint32_t div_up(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

}  // namespace gib
