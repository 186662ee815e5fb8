// Runs a compiled graph: allocates the plan's resources, uploads the scene (again each frame
// when it moves), records every running pass between a timestamp pair and a debug label with
// the barriers the plan placed, and reads back GPU time per pass. Optionally scans every
// resource a pass writes for NaN / Inf / out-of-domain values on the GPU (stability.h).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "renderer/image/float_image.h"
#include "renderer/graph/pass.h"
#include "renderer/graph/stability.h"

namespace gib {

struct LoggedDispatch;

// One compute dispatch of a pass, with the executor's dispatch profile on.
struct DispatchTiming {
  uint64_t threads = 0;  // groups x workgroup size (indirect: the groups read back after the frame)
  bool indirect = false;
  // GPU only (NaN on a CPU device, or past the profile's timestamp limit): from the pass's
  // start, or the previous dispatch's timestamp, to the one written right after this dispatch;
  // barriers and fills recorded before it count to it.
  double ms = 0;
  // The pipeline it ran (name, Pipeline::statistics); owned by the Gpu's pipeline cache, so valid
  // while the Gpu lives.
  const Pipeline* pipeline = nullptr;
};

struct PassTiming {
  std::string name;
  double ms = 0;
  std::vector<DispatchTiming> dispatches;  // with the dispatch profile on, in record order
};

struct FrameResult {
  uint32_t frame = 0;
  std::vector<PassTiming> passes;  // running passes, execution order
  double total_ms = 0;             // first timestamp to last, less the stability scans
  double scan_ms = 0;              // stability scans (GPU: between timestamps; CPU: host clock)
  uint32_t scan_dispatches = 0;    // stability scan dispatches this frame
};

// A graph-level override of a named resource: each frame, right after `after_pass` records,
// `resource` (a resource that pass writes) is overwritten with `data`: an image's tightly
// packed texels in its own format, or a buffer's bytes (one copy). Error attribution puts a
// stage's oracle in its output this way, so no technique code changes; the graph stays
// technique-agnostic (any pass, any written resource). Stability scans after the pass see the
// override; on a CPU device the copy counts to the pass's host time. An override holds over the
// executor frames first_frame..last_frame (0-based, inclusive): an oracle that follows a moving
// scene is a sequence of overrides of one resource over consecutive frame ranges.
struct ResourceOverride {
  std::string after_pass;
  std::string resource;
  std::vector<uint8_t> data;
  uint32_t first_frame = 0, last_frame = UINT32_MAX;
};

class Executor {
 public:
  Executor(Gpu& gpu, const Scene& scene, Settings settings, std::vector<std::unique_ptr<Pass>> passes,
           std::vector<std::string> outputs);
  ~Executor();
  const Plan& plan() const { return plan_; }
  const Settings& settings() const { return settings_; }
  Gpu& gpu() const { return gpu_; }
  FrameResult run_frame();
  // `n` frames; on a GPU in one submission (one host wait for all), a moving scene's frames one
  // at a time (each uploads the scene first). Same commands and output as n run_frame calls.
  std::vector<FrameResult> run_frames(uint32_t n);
  // Whether passes are timed by the host clock around one submission each (the default on a
  // CPU device, where in-submission timestamps misattribute work; frames then run one at a
  // time) or by GPU timestamps in a submission per frame batch (the default on a GPU).
  void time_passes_on_host(bool on) { host_timed_passes_ = on; }
  uint32_t frames_run() const { return frame_; }
  // Bytes of the packed image-texture buffer (tables, every texture and mip; 0 before the
  // first frame uploads it).
  uint64_t texture_bytes() const { return texture_bytes_; }
  // Stability scan (off by default): from the next frame on, after each running pass, one
  // compute dispatch per resource the pass writes (write / read_write) whose declared value
  // domain is not none reduces it to per-category counts and first offending texel; the
  // executor reads the small result buffer back once per frame and accumulates stability().
  // Pass timings exclude it: on a GPU it is recorded after the pass's end timestamp, on a CPU
  // device it is its own submission after the pass's host-timed one.
  void enable_stability_scan(bool on = true) { scan_enabled_ = on; }
  // Dispatch profile (off by default): every compute dispatch a pass records is logged with its
  // thread count, and on a GPU a timestamp is written after each (which may serialise
  // dispatches the pass left unbarriered: bench profiles frames apart from its timed ones).
  void enable_dispatch_profile(bool on = true) { profile_dispatches_ = on; }
  bool stability_scan_enabled() const { return scan_enabled_; }
  const StabilityReport& stability() const { return stability_; }
  // Adds an override (above); throws GraphError naming the pass, the resource and what was
  // expected when the pass does not run, does not write the resource, or the size differs.
  void add_override(const ResourceOverride& o);
  // Any image resource of the plan as float texels (ids and packed formats decoded to floats).
  FloatImage read(const std::string& name);
  std::vector<std::string> image_names() const;
  // Raw bytes of a buffer resource of the plan (the copy written most recently).
  std::vector<uint8_t> read_buffer(const std::string& name);
  // Raw bytes of any resource of the plan: a buffer's, or an image's tightly packed texels in
  // its own format (ids and packed encodings as stored: what add_override takes).
  std::vector<uint8_t> read_bytes(const std::string& name);

 private:
  std::map<std::string, ResolvedSlot> bind_slots(const PassDecl& decl);
  struct ScanTarget;
  void plan_stability_scan();
  void zero_persistent();
  // Scans after a pass into results buffer `slot` (a frame's place in its batch).
  uint32_t record_scans(Cmd& cmd, size_t running_index, bool& reset, uint32_t slot);
  void collect_scan_results(uint32_t slot, uint32_t frame);
  float frame_time() const;
  void record_pass(Cmd& cmd, const PlannedPass& pass, size_t running_index, uint32_t& query,
                   uint32_t profile_query_limit, std::vector<LoggedDispatch>& logged);
  FrameResult run_frame_host_timed();
  std::vector<FrameResult> run_batch(uint32_t n);
  void upload_scene(float time);
  // The frame's constants, written by the frame's first command buffer (no upload of its own).
  void record_frame_constants(Cmd& cmd, float time);
  Gpu& gpu_;
  const Scene& scene_;
  Settings settings_;
  std::vector<std::unique_ptr<Pass>> passes_;
  std::vector<PassDecl> decls_;
  Plan plan_;
  SceneGpu scene_gpu_;
  // bake_average_opacity(scene_), once: an animated scene is flattened every frame.
  std::vector<float> average_opacity_;
  uint64_t texture_bytes_ = 0;
  std::vector<GpuDecal> decals_;  // world space (offset applied), copied into each frame's constants
  std::vector<IndoorVolume> indoor_volumes_;  // carried by the frame constants
  struct Allocation {
    std::shared_ptr<Image> image[2];
    std::shared_ptr<Buffer> buffer[2];
    bool ping_pong = false;
  };
  // Of a ping-pong resource's two copies: the one this frame's passes write, and the one
  // written most recently once run_frame has advanced frame_ (0 for a single copy).
  int written_copy(const Allocation& a) const { return a.ping_pong ? int(frame_ & 1) : 0; }
  int latest_copy(const Allocation& a) const { return a.ping_pong ? int((frame_ + 1) & 1) : 0; }
  std::map<std::string, Allocation> allocations_;
  uint32_t frame_ = 0;
  bool scene_uploaded_ = false;
  bool scan_enabled_ = false;
  bool host_timed_passes_ = false;
  bool profile_dispatches_ = false;
  struct Override {
    size_t running_index = 0;
    uint32_t first_frame = 0, last_frame = UINT32_MAX;
    std::string resource;
    std::shared_ptr<Image> image;
    std::shared_ptr<Buffer> buffer;
  };
  std::vector<Override> overrides_;
  void record_overrides(Cmd& cmd, size_t running_index);
  std::vector<ScanTarget> scan_targets_;       // execution order, slot order
  std::vector<std::vector<size_t>> scan_of_pass_;  // per running pass: indices into scan_targets_
  std::vector<std::shared_ptr<Buffer>> scan_results_;  // per frame of a batch
  StabilityReport stability_;
  float prev_view_proj_[16] = {};
};

// Converts raw texels of `format` to floats (1-4 channels as the format has, depth 1).
FloatImage decode_texels(Format format, uint32_t width, uint32_t height, const std::vector<uint8_t>& raw);

}  // namespace gib
