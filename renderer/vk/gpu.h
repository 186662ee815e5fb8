// The Vulkan layer's public face. Nothing here exposes a Vulkan type: the graph, the passes
// and the harness talk to the GPU through these handles, and only renderer/vk/*.cpp includes
// <vulkan/vulkan.h>. One Gpu per process run; everything it creates dies with it.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image/format.h"

namespace gib {

struct GpuError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;         // discrete, integrated, virtual, cpu, other
  std::string driver_name;  // e.g. llvmpipe, NVIDIA
  std::string driver_info;  // e.g. "Mesa 22.3.6 (LLVM 15.0.6)", "580.65"
  std::string api_version;  // "1.3.230"
  uint32_t subgroup_size = 0;
  // Subgroup operations the compute stage supports (Vulkan 1.1): what a shader may use.
  bool subgroup_vote = false;    // subgroupAllEqual
  bool subgroup_ballot = false;  // subgroupBallot, subgroupBroadcastFirst
  bool subgroup_arithmetic = false;  // subgroupOr, subgroupAdd
  double timestamp_period_ns = 0;  // 0: no timestamps on the compute queue
  // Threads the device can hold resident at once (its compute units x the most threads one
  // unit keeps in flight), from VK_NV_shader_sm_builtins (SMs x warps per SM x 32) or
  // VK_AMD_shader_core_properties; 0 where the driver does not say (lavapipe). bench's
  // occupancy term needs it (perf/occupancy.h).
  uint32_t compute_units = 0;
  uint64_t resident_threads = 0;
  std::string residency_source;  // the extension it came from
  bool is_default = false;
  // Compute pipelines carry the driver's statistics of their compiled code (GpuOptions::
  // pipeline_statistics, where VK_KHR_pipeline_executable_properties is supported).
  bool pipeline_statistics = false;
  bool is_software() const { return type == "cpu"; }
};

struct GpuOptions {
  std::string device;     // "" default; an index; or a substring of the device name
  bool validate = false;  // Khronos validation layer + messenger (also env GIB_VALIDATE=1)
  // Capture each compute pipeline's statistics (VK_KHR_pipeline_executable_properties: register
  // count, shared memory, code size, as the driver names them) where the device supports it.
  // Off by default: capturing may bypass a driver's pipeline cache (bench turns it on).
  bool pipeline_statistics = false;
};

enum class BufferUsage : uint32_t { storage, uniform, indirect };
enum class DescriptorKind : uint32_t { storage_buffer, uniform_buffer, storage_image, sampled_image };

struct BindingDecl {
  uint32_t binding;
  DescriptorKind kind;
};

class Gpu;
class Buffer {
 public:
  virtual ~Buffer() = default;
  virtual uint64_t size() const = 0;
};
class Image {
 public:
  virtual ~Image() = default;
  virtual Format format() const = 0;
  virtual uint32_t width() const = 0;
  virtual uint32_t height() const = 0;
};
// One statistic of a compiled pipeline executable, as the driver reports it
// (VkPipelineExecutableStatisticKHR): e.g. NVIDIA's "Register Count", Mesa's "SSA values".
struct PipelineStatistic {
  std::string executable;  // the executable's name (a pipeline may compile to several)
  std::string name;
  std::string description;
  double value = 0;        // a boolean reads 0 / 1
};

class Pipeline {
 public:
  virtual ~Pipeline() = default;
  virtual const std::string& name() const = 0;
  // A compute pipeline's workgroup size (from its SPIR-V); {0, 0, 0} for a graphics pipeline.
  virtual std::array<uint32_t, 3> local_size() const = 0;
  // What the driver reported of its compiled code (DeviceInfo::pipeline_statistics); empty
  // where it was not captured.
  virtual const std::vector<PipelineStatistic>& statistics() const = 0;
};

// The LocalSize execution mode of a SPIR-V module's first compute entry point ({0, 0, 0}
// when there is none, or the words are not SPIR-V).
std::array<uint32_t, 3> spirv_local_size(std::span<const uint32_t> words);

struct Bind {
  uint32_t binding;
  const Buffer* buffer = nullptr;
  const Image* image = nullptr;
};

struct SpecConstant {
  uint32_t id;
  uint32_t value;  // reinterpret floats with std::bit_cast
};

struct ComputePipelineDesc {
  std::string shader;  // embedded name, e.g. "path_trace.comp"
  std::vector<BindingDecl> bindings;
  uint32_t push_constant_bytes = 0;
  std::vector<SpecConstant> spec_constants;
};

struct GraphicsPipelineDesc {
  std::string vertex_shader, fragment_shader;
  std::vector<BindingDecl> bindings;
  uint32_t push_constant_bytes = 0;
  std::vector<Format> color_formats;
  bool depth = true;  // D32 depth test (less), depth write
};

// Pipeline stage classes for barriers. The graph's PassKind masks use the same bits (1 <<
// PassKind; checked in renderer/graph/pass.h).
inline constexpr uint32_t kStageCompute = 1u << 0;
inline constexpr uint32_t kStageGraphics = 1u << 1;
inline constexpr uint32_t kStageTransfer = 1u << 2;
inline constexpr uint32_t kStageHost = 1u << 8;

// A command list under construction. Recording is cheap; submit() runs it and waits.
class Cmd {
 public:
  virtual ~Cmd() = default;
  virtual void bind(const Pipeline& pipeline, std::span<const Bind> binds,
                    const void* push = nullptr, uint32_t push_bytes = 0) = 0;
  virtual void dispatch(uint32_t x, uint32_t y = 1, uint32_t z = 1) = 0;
  virtual void dispatch_indirect(const Buffer& args, uint64_t offset) = 0;
  virtual void begin_rendering(std::span<const Image* const> colors, const Image* depth,
                               const float clear_color[4]) = 0;
  // Viewport and scissor inside the current rendering area (begin_rendering sets them to all of it).
  virtual void set_viewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height) = 0;
  virtual void draw(uint32_t vertex_count) = 0;
  virtual void end_rendering() = 0;
  virtual void barrier(uint32_t src_stages, uint32_t dst_stages) = 0;  // global memory barrier
  virtual void fill(const Buffer& buffer, uint32_t value) = 0;
  // Host data written from the command stream at its place in it: at most 65536 bytes, a
  // multiple of 4, from the start of the buffer (a transfer write).
  virtual void update(const Buffer& buffer, const void* data, uint32_t bytes) = 0;
  virtual void clear(const Image& image, const float value[4]) = 0;  // float or uint formats
  virtual void copy(const Image& src, const Image& dst) = 0;         // same format and extent
  virtual void copy(const Buffer& src, const Buffer& dst) = 0;       // same size
  virtual void timestamp(uint32_t query) = 0;                        // bottom-of-pipe
  virtual void begin_label(const std::string& name) = 0;
  virtual void end_label() = 0;
};

class Gpu {
 public:
  static std::unique_ptr<Gpu> create(const GpuOptions& options);
  static std::vector<DeviceInfo> list_devices();  // with is_default set
  virtual ~Gpu() = default;

  virtual const DeviceInfo& info() const = 0;
  virtual std::shared_ptr<Buffer> create_buffer(uint64_t bytes, BufferUsage usage,
                                                const std::string& debug_name) = 0;
  virtual std::shared_ptr<Image> create_image(Format format, uint32_t width, uint32_t height,
                                              const std::string& debug_name) = 0;
  virtual void upload(const Buffer& dst, const void* data, uint64_t bytes, uint64_t offset = 0) = 0;
  virtual void download(const Buffer& src, void* data, uint64_t bytes, uint64_t offset = 0) = 0;
  virtual void upload(const Image& dst, const void* texels, uint64_t bytes) = 0;  // tightly packed
  virtual std::vector<uint8_t> download(const Image& src) = 0;  // tightly packed texels
  // Pipelines are cached by their description; creating the same one twice is free.
  virtual std::shared_ptr<Pipeline> compute_pipeline(const ComputePipelineDesc& desc) = 0;
  virtual std::shared_ptr<Pipeline> graphics_pipeline(const GraphicsPipelineDesc& desc) = 0;

  // Timestamps: queries are indices into a per-submission pool of `query_count` entries.
  virtual std::unique_ptr<Cmd> begin(uint32_t query_count = 0) = 0;
  // Runs the commands and waits. Returns the timestamps (ns since an arbitrary origin; masked
  // to the queue's valid bits) of every query written.
  virtual std::vector<double> submit(std::unique_ptr<Cmd> cmd) = 0;

  // Validation messages (warnings and errors) seen so far; tests fail on any.
  virtual std::vector<std::string> validation_messages() const = 0;
  virtual void clear_validation_messages() = 0;
  virtual bool validating() const = 0;
};

const std::map<std::string, std::span<const uint32_t>>& shader_registry();

}  // namespace gib
