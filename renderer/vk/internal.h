// Concrete Vulkan objects behind gpu.h. Included only by renderer/vk/*.cpp.
#pragma once
#include <vulkan/vulkan.h>

#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "renderer/vk/gpu.h"

namespace gib::vkimpl {

void check(VkResult r, const char* what);
VkFormat to_vk(Format f);
bool is_uint_format(Format f);

class VkGpu;

class VkBufferObj final : public Buffer {
 public:
  VkBufferObj(VkGpu& gpu, uint64_t bytes, BufferUsage usage, const std::string& name);
  ~VkBufferObj() override;
  uint64_t size() const override { return bytes_; }
  VkBuffer handle = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // non-null when host visible
 private:
  VkGpu& gpu_;
  uint64_t bytes_;
};

class VkImageObj final : public Image {
 public:
  VkImageObj(VkGpu& gpu, Format format, uint32_t w, uint32_t h, const std::string& name);
  ~VkImageObj() override;
  Format format() const override { return format_; }
  uint32_t width() const override { return w_; }
  uint32_t height() const override { return h_; }
  VkImage handle = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
 private:
  VkGpu& gpu_;
  Format format_;
  uint32_t w_, h_;
};

class VkPipelineObj final : public Pipeline {
 public:
  ~VkPipelineObj() override;
  const std::string& name() const override { return name_; }
  std::array<uint32_t, 3> local_size() const override { return local_size_; }
  const std::vector<PipelineStatistic>& statistics() const override { return statistics_; }
  std::string name_;
  std::vector<PipelineStatistic> statistics_;
  std::array<uint32_t, 3> local_size_{0, 0, 0};
  VkDevice device = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
  std::vector<BindingDecl> bindings;
  uint32_t push_bytes = 0;
};

class VkGpu final : public Gpu {
 public:
  VkGpu(const GpuOptions& options);
  ~VkGpu() override;
  const DeviceInfo& info() const override { return info_; }
  std::shared_ptr<Buffer> create_buffer(uint64_t bytes, BufferUsage usage, const std::string& name) override;
  std::shared_ptr<Image> create_image(Format format, uint32_t w, uint32_t h, const std::string& name) override;
  void upload(const Buffer& dst, const void* data, uint64_t bytes, uint64_t offset) override;
  void download(const Buffer& src, void* data, uint64_t bytes, uint64_t offset) override;
  void upload(const Image& dst, const void* texels, uint64_t bytes) override;
  std::vector<uint8_t> download(const Image& src) override;
  std::shared_ptr<Pipeline> compute_pipeline(const ComputePipelineDesc& desc) override;
  std::shared_ptr<Pipeline> graphics_pipeline(const GraphicsPipelineDesc& desc) override;
  std::unique_ptr<Cmd> begin(uint32_t query_count) override;
  std::vector<double> submit(std::unique_ptr<Cmd> cmd) override;
  std::vector<std::string> validation_messages() const override;
  void clear_validation_messages() override;
  bool validating() const override { return messenger_ != VK_NULL_HANDLE; }

  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback) const;
  void set_name(VkObjectType type, uint64_t handle, const std::string& name);
  void one_shot(const std::function<void(VkCommandBuffer)>& record);
  void add_message(std::string msg);

  // Objects every frame needs again are kept for the next one instead of created and destroyed
  // each time: on NVIDIA's driver each creation is a kernel call, and a 128x72 frame of about
  // 1 ms of GPU work spent more system CPU on them than the GPU spent on the frame.
  VkDescriptorPool take_descriptor_pool();
  void keep_descriptor_pool(VkDescriptorPool pool);  // resets it
  VkQueryPool take_query_pool(uint32_t count);
  void keep_query_pool(VkQueryPool pool, uint32_t count);
  VkFence submit_fence();  // unsignalled; reset after each wait
  // Submits one ended command buffer and waits for it (fence reset after), alone on the GPU
  // among the processes that share its submit lock (submit_lock.h).
  void submit_and_wait(VkCommandBuffer cb);
  struct Staging {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    uint64_t bytes = 0;
  };
  // A host-visible buffer of at least `bytes`, valid until the next call: the one kept (grown as
  // needed, up to kKeptStagingBytes) or, above that, `temporary`, which the caller destroys.
  Staging& staging(uint64_t bytes, Staging& temporary);
  void destroy_staging(Staging& s);
  static constexpr uint64_t kKeptStagingBytes = 64ull << 20;

  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  uint32_t timestamp_valid_bits = 0;
  VkPhysicalDeviceMemoryProperties memory_props{};
  VkSampler nearest_sampler = VK_NULL_HANDLE;  // for sampled_image bindings (format checks)
  VkCommandPool command_pool() const { return pool_; }
  PFN_vkCmdBeginDebugUtilsLabelEXT begin_label_fn = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT end_label_fn = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT set_name_fn = nullptr;
  PFN_vkGetPipelineExecutablePropertiesKHR executable_properties_fn = nullptr;  // info_.pipeline_statistics
  PFN_vkGetPipelineExecutableStatisticsKHR executable_statistics_fn = nullptr;

 private:
  DeviceInfo info_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  mutable std::mutex messages_mutex_;
  std::vector<std::string> messages_;
  std::map<std::string, std::shared_ptr<Pipeline>> pipelines_;
  std::vector<VkDescriptorPool> free_descriptor_pools_;
  std::multimap<uint32_t, VkQueryPool> free_query_pools_;
  VkFence fence_ = VK_NULL_HANDLE;
  Staging staging_;
  Staging make_staging(uint64_t bytes);
  // kGibSpecNativeHalfRne's value for every compute pipeline (device_spec_shared.h).
  uint32_t native_half_rne_ = 0;
  bool probe_half_rounding();
};

class VkCmd final : public Cmd {
 public:
  VkCmd(VkGpu& gpu, VkCommandPool pool, uint32_t query_count);
  ~VkCmd() override;
  void bind(const Pipeline& pipeline, std::span<const Bind> binds, const void* push, uint32_t push_bytes) override;
  void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
  void dispatch_indirect(const Buffer& args, uint64_t offset) override;
  void begin_rendering(std::span<const Image* const> colors, const Image* depth, const float clear_color[4]) override;
  void set_viewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height) override;
  void draw(uint32_t vertex_count) override;
  void end_rendering() override;
  void barrier(uint32_t src_stages, uint32_t dst_stages) override;
  void fill(const Buffer& buffer, uint32_t value) override;
  void update(const Buffer& buffer, const void* data, uint32_t bytes) override;
  void clear(const Image& image, const float value[4]) override;
  void copy(const Image& src, const Image& dst) override;
  void copy(const Buffer& src, const Buffer& dst) override;
  void timestamp(uint32_t query) override;
  void begin_label(const std::string& name) override;
  void end_label() override;

  VkGpu& gpu;
  VkCommandPool pool;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  VkQueryPool queries = VK_NULL_HANDLE;
  uint32_t query_count = 0;
  uint32_t queries_written = 0;
  static constexpr uint32_t kSetsPerPool = 64;
 private:
  VkDescriptorPool descriptor_pool();
  std::vector<VkDescriptorPool> descriptor_pools_;
  uint32_t sets_in_pool_ = 0;
};

}  // namespace gib::vkimpl
