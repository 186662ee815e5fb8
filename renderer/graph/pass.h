// The pass interface: a pass declares its slots (pure, no GPU) and records its dispatches
// against the resources the graph allocated for exactly those slots.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/gpu.h"

namespace gib {

// radiance-cache (idTech 8 GI) settings; presets and case options set them. Design notes:
// renderer/techniques/radiance_cache.md.
struct RadianceCacheSettings {
  uint32_t cascades = 3;            // irradiance-volume cascades (16^3 probes each), one updated per frame
  float probe_spacing = 0.5f;       // metres between cascade-0 probes; doubles per cascade
  uint32_t rays_per_probe = 32;     // visibility rays per updated probe (16 / 32 / 64)
  float probe_hysteresis = 0.85f;   // weight of last frame's probe texel when blending
  uint32_t gather_divisor = 2;      // final gather at 1/2 or 1/4 resolution
  uint32_t cache_log2_cells = 15;   // world radiance cache capacity (2^n cells)
  uint32_t cache_max_probe = 8;     // linear-probing steps before an insertion is dropped
  float cache_cell_size = 0.25f;    // metres at LOD 0
  float cache_lod_distance = 8.0f;  // metres: LOD = 2^floor(log2(1 + dist / this))
  uint32_t cache_reuse_frames = 4;  // a shaded cell is reused this many frames
  uint32_t light_grid_cascades = 4; // 16^3 cells each, first cascade light_grid_extent metres wide
  float light_grid_extent = 32.0f;
  bool visibility_test = true;      // leak mitigation: Chebyshev test on RG16F probe moments
  float normal_bias = 0.1f;         // leak mitigation: metres along the normal before sampling probes
  float view_bias = 0.1f;           // leak mitigation: metres towards the viewer
  bool probe_rays = true;           // leak mitigation: a shadow ray from the sampled point to each of its 8 probes; blocked ones get no weight
  bool cache_side_key = true;       // leak mitigation: cache cells keyed by surface side, so the two faces of a thin wall differ
  bool disocclusion = true;         // temporal filter rejects history failing depth/normal tests
  uint32_t history_format = 0;      // 0 RGB9E5 (R32_UINT), 1 RGBA16F, 2 R11G11B10F, 3 RGBA32F
  uint32_t history_max_frames = 16; // n_max of the temporal filter
  uint32_t denoise_radius = 3;      // bilateral half-width in gather pixels
  bool multi_bounce = true;         // 0: no cache feeds back on itself (single bounce; white-furnace negative control)
  bool pre_exposure = true;         // screen-space GI works on radiance x P (exposure pass); 0: P = 1 (negative control)
};

// Robustness debugging (technique options inject_nan, inject_frame, inject_x, inject_y): the pass
// that writes the target resource writes a NaN into it on one frame.
struct DebugSettings {
  uint32_t inject_nan = 0;    // 0 none, 1 gbuffer_normal texel (gbuffer), 2 radiance-cache cell radiance
                              // (radiance_cache_shade), 3 one path-tracer sample (path_trace)
  uint32_t inject_frame = 0;  // frame index (RecordContext::frame, 0-based) of the injection
  uint32_t inject_x = 0, inject_y = 0;  // pixel (render resolution); target 2: the cell of that pixel's surface
  bool injects(uint32_t target, uint32_t frame) const { return inject_nan == target && frame == inject_frame; }
};

struct Settings {
  uint32_t width = 256, height = 144;
  uint32_t seed = 1;
  std::string preset = "medium";
  uint32_t spp_per_frame = 1;  // reference: samples per pixel added each frame
  uint32_t max_bounces = 8;    // reference: path length cap (Russian roulette after 3)
  uint32_t sky_rays = 4;       // direct: sky visibility rays per pixel
  // >= 0: every frame renders the scene at this time (seconds): a reference of one moment of
  // an animated scene. < 0: frame f renders at f * scene.frame_time.
  float scene_time = -1.0f;
  // Every pass that reads history, blends or accumulates drops/repairs non-finite values (and
  // gib_surface/gbuffer/direct_lighting repair non-finite normals). 0 turns them all off (negative control).
  bool nan_guards = true;
  // Metres added to every world-space position (vertices, lights, camera position and target)
  // when the executor uploads the scene: the far-from-origin stress case (options
  // world_offset_x/y/z). The image is unchanged in exact arithmetic.
  Vec3 world_offset{0, 0, 0};
  RadianceCacheSettings rc;
  DebugSettings debug;
};

// The scene as GPU buffers, in the binding order of frame_shared.h / scene.glsl.
struct SceneGpu {
  std::shared_ptr<Buffer> frame;  // GpuFrame (uniform)
  std::array<std::shared_ptr<Buffer>, 7> buffers;
  uint32_t triangle_count = 0;
  uint32_t instance_count = 0;
  uint32_t light_count = 0;
  // Binds for frame + scene buffers (bindings 0..7).
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

// Descriptor layout of the scene bundle (frame uniform at 0, scene buffers at 1..7); a pass
// appends its own slots from binding 8 (kBindPassFirst).
std::vector<BindingDecl> scene_bindings();

// The common shape of a compute pass: the scene bundle plus storage images bound by slot name,
// one dispatch. Push constants and specialization constants optional.
// prev: bind last frame's copy of a ping-pong resource (the slot declares read_prev).
struct ImageBinding {
  uint32_t binding;
  const char* slot;
  bool prev = false;
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
};
void record_compute(RecordContext& ctx, const ComputeDispatch& d);

inline uint32_t div_up(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

}  // namespace gib
