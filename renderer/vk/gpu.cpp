// Instance, device choice, memory, buffers, images, uploads and readbacks.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>

#include "renderer/vk/internal.h"
#include "renderer/vk/submit_lock.h"
#include "device_spec_shared.h"
#include "renderer/codecs/half.h"

namespace gib {
namespace vkimpl {

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw GpuError(fmt::format("vulkan: {} failed (VkResult {})", what, static_cast<int>(r)));
}

VkFormat to_vk(Format f) {
  switch (f) {
    case Format::r32_uint: return VK_FORMAT_R32_UINT;
    case Format::rg32_uint: return VK_FORMAT_R32G32_UINT;
    case Format::rgba32_uint: return VK_FORMAT_R32G32B32A32_UINT;
    case Format::r32_float: return VK_FORMAT_R32_SFLOAT;
    case Format::rg32_float: return VK_FORMAT_R32G32_SFLOAT;
    case Format::rgba32_float: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::rg16_float: return VK_FORMAT_R16G16_SFLOAT;
    case Format::rgba16_float: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::rgba16_uint: return VK_FORMAT_R16G16B16A16_UINT;
    case Format::rgba8_unorm: return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::b10g11r11_float: return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    case Format::e5b9g9r9_float: return VK_FORMAT_E5B9G9R9_UFLOAT_PACK32;
    case Format::d32_float: return VK_FORMAT_D32_SFLOAT;
    case Format::buffer: break;
  }
  throw GpuError("vulkan: a buffer has no image format");
}

bool is_uint_format(Format f) {
  return f == Format::r32_uint || f == Format::rg32_uint || f == Format::rgba32_uint || f == Format::rgba16_uint;
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT && data && data->pMessage)
    static_cast<VkGpu*>(user)->add_message(data->pMessage);
  return VK_FALSE;
}

std::string version_string(uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v), VK_API_VERSION_PATCH(v));
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

bool has_layer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

bool has_instance_extension(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

VkInstance make_instance(bool validate, bool* debug_utils) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "gibench";
  app.apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> layers, exts;
  *debug_utils = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (*debug_utils) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (validate) {
    if (!has_layer("VK_LAYER_KHRONOS_validation"))
      throw GpuError("vulkan: validation requested but VK_LAYER_KHRONOS_validation is not installed (package vulkan-validationlayers)");
    layers.push_back("VK_LAYER_KHRONOS_validation");
  }
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<uint32_t>(exts.size());
  ci.ppEnabledExtensionNames = exts.data();
  VkInstance inst = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &inst);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw GpuError("vulkan: no Vulkan driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
  check(r, "vkCreateInstance");
  return inst;
}

bool has_device_extension(VkPhysicalDevice dev, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// Compute units and resident threads, where the driver tells them (DeviceInfo).
void read_residency(VkPhysicalDevice dev, DeviceInfo& info) {
  if (has_device_extension(dev, VK_NV_SHADER_SM_BUILTINS_EXTENSION_NAME)) {
    VkPhysicalDeviceShaderSMBuiltinsPropertiesNV sm{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SM_BUILTINS_PROPERTIES_NV};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &sm;
    vkGetPhysicalDeviceProperties2(dev, &props);
    info.compute_units = sm.shaderSMCount;
    info.resident_threads = uint64_t(sm.shaderSMCount) * sm.shaderWarpsPerSM * 32u;
    info.residency_source = fmt::format("VK_NV_shader_sm_builtins: {} SMs x {} warps x 32", sm.shaderSMCount, sm.shaderWarpsPerSM);
  } else if (has_device_extension(dev, VK_AMD_SHADER_CORE_PROPERTIES_EXTENSION_NAME)) {
    VkPhysicalDeviceShaderCorePropertiesAMD core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CORE_PROPERTIES_AMD};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &core;
    vkGetPhysicalDeviceProperties2(dev, &props);
    info.compute_units = core.shaderEngineCount * core.shaderArraysPerEngineCount * core.computeUnitsPerShaderArray;
    info.resident_threads = uint64_t(info.compute_units) * core.simdPerComputeUnit * core.wavefrontsPerSimd * core.wavefrontSize;
    info.residency_source = fmt::format("VK_AMD_shader_core_properties: {} CUs x {} SIMDs x {} waves x {}", info.compute_units,
                                        core.simdPerComputeUnit, core.wavefrontsPerSimd, core.wavefrontSize);
  }
}

struct Candidate {
  VkPhysicalDevice handle;
  DeviceInfo info;
  uint32_t queue_family;
};

std::vector<Candidate> enumerate(VkInstance inst) {
  uint32_t n = 0;
  check(vkEnumeratePhysicalDevices(inst, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devs(n);
  check(vkEnumeratePhysicalDevices(inst, &n, devs.data()), "vkEnumeratePhysicalDevices");
  std::vector<Candidate> out;
  for (uint32_t i = 0; i < n; ++i) {
    VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties drv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    sub.pNext = &drv;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &sub;
    vkGetPhysicalDeviceProperties2(devs[i], &props);
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(devs[i], &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qf(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(devs[i], &qn, qf.data());
    uint32_t family = UINT32_MAX;
    for (uint32_t q = 0; q < qn; ++q)
      if ((qf[q].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[q].queueFlags & VK_QUEUE_COMPUTE_BIT)) { family = q; break; }
    if (family == UINT32_MAX) continue;
    Candidate c{devs[i], {}, family};
    c.info.index = i;
    c.info.name = props.properties.deviceName;
    c.info.type = type_name(props.properties.deviceType);
    c.info.driver_name = drv.driverName;
    c.info.driver_info = drv.driverInfo;
    c.info.api_version = version_string(props.properties.apiVersion);
    c.info.subgroup_size = sub.subgroupSize;
    const bool compute_ops = (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0;
    c.info.subgroup_vote = compute_ops && (sub.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT);
    c.info.subgroup_ballot = compute_ops && (sub.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT);
    c.info.subgroup_arithmetic = compute_ops && (sub.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT);
    c.info.timestamp_period_ns = qf[family].timestampValidBits ? props.properties.limits.timestampPeriod : 0.0;
    read_residency(devs[i], c.info);
    out.push_back(c);
  }
  // Default: first discrete, else first integrated, else anything (lavapipe).
  int best = -1, best_rank = 99;
  for (size_t i = 0; i < out.size(); ++i) {
    int rank = out[i].info.type == "discrete" ? 0 : out[i].info.type == "integrated" ? 1 : out[i].info.type == "cpu" ? 3 : 2;
    if (rank < best_rank) { best_rank = rank; best = static_cast<int>(i); }
  }
  if (best >= 0) out[best].info.is_default = true;
  return out;
}

const Candidate& choose(const std::vector<Candidate>& cands, const std::string& want) {
  if (cands.empty()) throw GpuError("vulkan: no device with a graphics+compute queue");
  if (want.empty()) {
    for (auto& c : cands) if (c.info.is_default) return c;
  }
  bool numeric = !want.empty() && want.find_first_not_of("0123456789") == std::string::npos;
  std::string names;
  for (auto& c : cands) {
    if (numeric ? c.info.index == static_cast<uint32_t>(std::stoul(want)) : c.info.name.find(want) != std::string::npos)
      return c;
    names += fmt::format("{}{}: {}", names.empty() ? "" : ", ", c.info.index, c.info.name);
  }
  throw GpuError(fmt::format("--device: expected an index or a name substring of one of [{}], got '{}'", names, want));
}

}  // namespace

VkGpu::VkGpu(const GpuOptions& options) {
  const char* env = std::getenv("GIB_VALIDATE");
  bool validate = options.validate || (env && std::string(env) == "1");
  bool debug_utils = false;
  instance = make_instance(validate, &debug_utils);
  if (validate && debug_utils) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    mi.pfnUserCallback = on_validation;
    mi.pUserData = this;
    check(create(instance, &mi, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
  if (debug_utils) {
    begin_label_fn = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance, "vkCmdBeginDebugUtilsLabelEXT"));
    end_label_fn = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance, "vkCmdEndDebugUtilsLabelEXT"));
    set_name_fn = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
  }
  auto cands = enumerate(instance);
  const Candidate& c = choose(cands, options.device);
  physical = c.handle;
  info_ = c.info;
  queue_family = c.queue_family;
  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qf(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, qf.data());
  timestamp_valid_bits = qf[queue_family].timestampValidBits;
  vkGetPhysicalDeviceMemoryProperties(physical, &memory_props);

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(physical, &f2);
  if (!f13.dynamicRendering || !f13.synchronization2)
    throw GpuError(fmt::format("vulkan: device '{}' lacks dynamicRendering/synchronization2 (Vulkan 1.3 required)", info_.name));
  // Enable only what we use, so behaviour matches between lavapipe and NVIDIA.
  VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  e13.dynamicRendering = VK_TRUE;
  e13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features e12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  e12.pNext = &e13;
  e12.hostQueryReset = f12.hostQueryReset;
  e12.scalarBlockLayout = f12.scalarBlockLayout;
  e12.shaderFloat16 = f12.shaderFloat16;
  VkPhysicalDeviceFeatures2 e2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  e2.pNext = &e12;
  // Pipeline statistics, only when asked (GpuOptions::pipeline_statistics) and supported.
  std::vector<const char*> device_exts;
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR exec{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  if (options.pipeline_statistics && has_device_extension(physical, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR have{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    query.pNext = &have;
    vkGetPhysicalDeviceFeatures2(physical, &query);
    if (have.pipelineExecutableInfo) {
      exec.pipelineExecutableInfo = VK_TRUE;
      e13.pNext = &exec;
      device_exts.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    }
  }
  e2.features.shaderInt64 = f2.features.shaderInt64;
  e2.features.shaderStorageImageWriteWithoutFormat = f2.features.shaderStorageImageWriteWithoutFormat;
  e2.features.shaderStorageImageReadWithoutFormat = f2.features.shaderStorageImageReadWithoutFormat;
  e2.features.fragmentStoresAndAtomics = f2.features.fragmentStoresAndAtomics;

  float prio = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queue_family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &prio;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &e2;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(device_exts.size());
  dci.ppEnabledExtensionNames = device_exts.data();
  check(vkCreateDevice(physical, &dci, nullptr, &device), "vkCreateDevice");
  if (!device_exts.empty()) {
    executable_properties_fn = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
        vkGetDeviceProcAddr(device, "vkGetPipelineExecutablePropertiesKHR"));
    executable_statistics_fn = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
        vkGetDeviceProcAddr(device, "vkGetPipelineExecutableStatisticsKHR"));
    info_.pipeline_statistics = executable_properties_fn && executable_statistics_fn;
  }
  vkGetDeviceQueue(device, queue_family, 0, &queue);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queue_family;
  check(vkCreateCommandPool(device, &pci, nullptr, &pool_), "vkCreateCommandPool");
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.unnormalizedCoordinates = VK_FALSE;
  check(vkCreateSampler(device, &sci, nullptr, &nearest_sampler), "vkCreateSampler");
  native_half_rne_ = probe_half_rounding() ? 1u : 0u;
}

// Whether packHalf2x16 rounds to nearest even here: the device converts, for a sample of half
// codes over every exponent (denormals included), the float halfway to the next code and the
// floats just either side of it, both signs, and values at and past the largest half; the CPU
// mirror (codecs::float_to_half) says what nearest-even gives. Ties tell nearest-even from
// ties-away, the neighbours tell nearest from toward-zero. Any difference: false, and
// gib_float_to_half corrects the device's result instead (packing.glsl).
bool VkGpu::probe_half_rounding() {
  std::vector<float> values = {65504.0f, std::nextafter(65520.0f, 0.0f), 65520.0f, 1.0e6f, 0.0f, -0.0f};
  for (uint32_t h = 0; h < 0x7bffu; h += (h < 64u || h > 0x7b00u) ? 1u : 37u) {
    const float lo = codecs::half_to_float(uint16_t(h)), hi = codecs::half_to_float(uint16_t(h + 1u));
    const float mid = 0.5f * (lo + hi);  // exact: 12 significant bits
    for (float v : {mid, std::nextafter(mid, 0.0f), std::nextafter(mid, 1.0e9f), lo}) {
      values.push_back(v);
      values.push_back(-v);
    }
  }
  const uint32_t count = uint32_t(values.size());
  auto in = create_buffer(count * sizeof(float), BufferUsage::storage, "half_rounding_probe.in");
  auto out = create_buffer(count * sizeof(uint32_t), BufferUsage::storage, "half_rounding_probe.out");
  upload(*in, values.data(), count * sizeof(float), 0);
  auto pipeline = compute_pipeline({"half_rounding_probe.comp",
                                    {{glsl::kHalfProbeBindIn, DescriptorKind::storage_buffer},
                                     {glsl::kHalfProbeBindOut, DescriptorKind::storage_buffer}},
                                    sizeof(uint32_t)});
  const Bind binds[] = {{glsl::kHalfProbeBindIn, in.get()}, {glsl::kHalfProbeBindOut, out.get()}};
  auto cmd = begin(0);
  cmd->bind(*pipeline, binds, &count, sizeof(count));
  cmd->dispatch((count + glsl::kHalfProbeGroup - 1) / glsl::kHalfProbeGroup);
  submit(std::move(cmd));
  std::vector<uint32_t> halves(count);
  download(*out, halves.data(), count * sizeof(uint32_t), 0);
  for (uint32_t i = 0; i < count; ++i)
    if (halves[i] != codecs::float_to_half(values[i])) return false;
  return true;
}

VkGpu::~VkGpu() {
  if (device) vkDeviceWaitIdle(device);
  pipelines_.clear();
  for (VkDescriptorPool dp : free_descriptor_pools_) vkDestroyDescriptorPool(device, dp, nullptr);
  for (auto& [count, qp] : free_query_pools_) vkDestroyQueryPool(device, qp, nullptr);
  if (fence_) vkDestroyFence(device, fence_, nullptr);
  destroy_staging(staging_);
  if (pool_) vkDestroyCommandPool(device, pool_, nullptr);
  if (nearest_sampler) vkDestroySampler(device, nearest_sampler, nullptr);
  if (device) vkDestroyDevice(device, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger_, nullptr);
  }
  if (instance) vkDestroyInstance(instance, nullptr);
}

void VkGpu::add_message(std::string msg) {
  std::lock_guard lock(messages_mutex_);
  messages_.push_back(std::move(msg));
}
std::vector<std::string> VkGpu::validation_messages() const {
  std::lock_guard lock(messages_mutex_);
  return messages_;
}
void VkGpu::clear_validation_messages() {
  std::lock_guard lock(messages_mutex_);
  messages_.clear();
}

uint32_t VkGpu::memory_type(uint32_t bits, VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback) const {
  for (VkMemoryPropertyFlags flags : {want, fallback})
    for (uint32_t i = 0; i < memory_props.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (memory_props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw GpuError("vulkan: no suitable memory type");
}

void VkGpu::set_name(VkObjectType type, uint64_t handle, const std::string& name) {
  if (!set_name_fn || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  ni.objectType = type;
  ni.objectHandle = handle;
  ni.pObjectName = name.c_str();
  set_name_fn(device, &ni);
}

void VkGpu::one_shot(const std::function<void(VkCommandBuffer)>& record) {
  VkCmd cmd(*this, pool_, 0);
  record(cmd.cb);
  check(vkEndCommandBuffer(cmd.cb), "vkEndCommandBuffer");
  submit_and_wait(cmd.cb);
}

void VkGpu::submit_and_wait(VkCommandBuffer cb) {
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  VkFence fence = submit_fence();
  {
    SubmitGuard alone;  // no other process's work on this GPU from submission to fence
    check(vkQueueSubmit(queue, 1, &si, fence), "vkQueueSubmit");
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  }
  check(vkResetFences(device, 1, &fence), "vkResetFences");
}

// ---------------------------------------------------------------- kept objects
VkDescriptorPool VkGpu::take_descriptor_pool() {
  if (!free_descriptor_pools_.empty()) {
    VkDescriptorPool dp = free_descriptor_pools_.back();
    free_descriptor_pools_.pop_back();
    return dp;
  }
  constexpr uint32_t kSetsPerPool = VkCmd::kSetsPerPool;
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSetsPerPool * 16},
                                  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSetsPerPool * 4},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kSetsPerPool * 16},
                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kSetsPerPool * 4}};
  VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  ci.maxSets = kSetsPerPool;
  ci.poolSizeCount = 4;
  ci.pPoolSizes = sizes;
  VkDescriptorPool dp;
  check(vkCreateDescriptorPool(device, &ci, nullptr, &dp), "vkCreateDescriptorPool");
  return dp;
}

void VkGpu::keep_descriptor_pool(VkDescriptorPool pool) {
  vkResetDescriptorPool(device, pool, 0);
  free_descriptor_pools_.push_back(pool);
}

VkQueryPool VkGpu::take_query_pool(uint32_t count) {
  auto it = free_query_pools_.find(count);
  if (it != free_query_pools_.end()) {
    VkQueryPool qp = it->second;
    free_query_pools_.erase(it);
    return qp;
  }
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = count;
  VkQueryPool qp;
  check(vkCreateQueryPool(device, &qi, nullptr, &qp), "vkCreateQueryPool");
  return qp;
}

void VkGpu::keep_query_pool(VkQueryPool pool, uint32_t count) { free_query_pools_.emplace(count, pool); }

VkFence VkGpu::submit_fence() {
  if (!fence_) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device, &fi, nullptr, &fence_), "vkCreateFence");
  }
  return fence_;
}

VkGpu::Staging VkGpu::make_staging(uint64_t bytes) {
  Staging st;
  st.bytes = bytes ? bytes : 4;
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = st.bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  check(vkCreateBuffer(device, &bi, nullptr, &st.buffer), "vkCreateBuffer (staging)");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, st.buffer, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memory_type(req.memoryTypeBits,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                                       VK_MEMORY_PROPERTY_HOST_CACHED_BIT,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkAllocateMemory(device, &ai, nullptr, &st.memory), "vkAllocateMemory (staging)");
  check(vkBindBufferMemory(device, st.buffer, st.memory, 0), "vkBindBufferMemory (staging)");
  check(vkMapMemory(device, st.memory, 0, VK_WHOLE_SIZE, 0, &st.mapped), "vkMapMemory (staging)");
  return st;
}

void VkGpu::destroy_staging(Staging& st) {
  if (st.buffer) vkDestroyBuffer(device, st.buffer, nullptr);
  if (st.memory) vkFreeMemory(device, st.memory, nullptr);
  st = Staging{};
}

VkGpu::Staging& VkGpu::staging(uint64_t bytes, Staging& temporary) {
  if (bytes > kKeptStagingBytes) {
    temporary = make_staging(bytes);
    return temporary;
  }
  if (staging_.bytes < bytes) {
    destroy_staging(staging_);
    // Grown in powers of two from 1 MiB, so a row's first readbacks settle it.
    uint64_t size = 1ull << 20;
    while (size < bytes) size *= 2;
    staging_ = make_staging(size);
  }
  return staging_;
}

// ---------------------------------------------------------------- buffers
VkBufferObj::VkBufferObj(VkGpu& gpu, uint64_t bytes, BufferUsage usage, const std::string& name)
    : gpu_(gpu), bytes_(bytes) {
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = bytes ? bytes : 4;
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
             VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (usage == BufferUsage::uniform) bi.usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  check(vkCreateBuffer(gpu.device, &bi, nullptr, &handle), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(gpu.device, handle, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = gpu.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  check(vkAllocateMemory(gpu.device, &ai, nullptr, &memory), "vkAllocateMemory (buffer)");
  check(vkBindBufferMemory(gpu.device, handle, memory, 0), "vkBindBufferMemory");
  auto flags = gpu.memory_props.memoryTypes[ai.memoryTypeIndex].propertyFlags;
  if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
    check(vkMapMemory(gpu.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  gpu.set_name(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(handle), name);
}

VkBufferObj::~VkBufferObj() {
  vkDestroyBuffer(gpu_.device, handle, nullptr);
  vkFreeMemory(gpu_.device, memory, nullptr);
}

std::shared_ptr<Buffer> VkGpu::create_buffer(uint64_t bytes, BufferUsage usage, const std::string& name) {
  return std::make_shared<VkBufferObj>(*this, bytes, usage, name);
}

namespace {
// A host-visible staging buffer for transfers to and from device-local memory.
// The staging memory of one transfer: the kept buffer, or a temporary one above its size.
struct StagingUse {
  VkGpu& gpu;
  VkGpu::Staging temporary;
  VkGpu::Staging& s;
  StagingUse(VkGpu& g, uint64_t bytes) : gpu(g), s(g.staging(bytes, temporary)) {}
  ~StagingUse() {
    if (temporary.buffer) gpu.destroy_staging(temporary);
  }
  StagingUse(const StagingUse&) = delete;
  StagingUse& operator=(const StagingUse&) = delete;
};

void host_to_device_barrier(VkCommandBuffer cb) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cb, &di);
}
}  // namespace

void VkGpu::upload(const Buffer& dst_, const void* data, uint64_t bytes, uint64_t offset) {
  auto& dst = static_cast<const VkBufferObj&>(dst_);
  if (offset + bytes > dst.size()) throw GpuError("upload: range exceeds buffer size");
  if (bytes == 0) return;
  StagingUse use(*this, bytes);
  std::memcpy(use.s.mapped, data, bytes);
  one_shot([&](VkCommandBuffer cb) {
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(cb, use.s.buffer, dst.handle, 1, &region);
    host_to_device_barrier(cb);
  });
}

void VkGpu::download(const Buffer& src_, void* data, uint64_t bytes, uint64_t offset) {
  auto& src = static_cast<const VkBufferObj&>(src_);
  if (offset + bytes > src.size()) throw GpuError("download: range exceeds buffer size");
  if (bytes == 0) return;
  StagingUse use(*this, bytes);
  one_shot([&](VkCommandBuffer cb) {
    host_to_device_barrier(cb);
    VkBufferCopy region{offset, 0, bytes};
    vkCmdCopyBuffer(cb, src.handle, use.s.buffer, 1, &region);
  });
  std::memcpy(data, use.s.mapped, bytes);
}

// ---------------------------------------------------------------- images
VkImageObj::VkImageObj(VkGpu& gpu, Format format, uint32_t w, uint32_t h, const std::string& name)
    : gpu_(gpu), format_(format), w_(w), h_(h) {
  VkFormat vf = to_vk(format);
  bool depth = format == Format::d32_float;
  aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(gpu.physical, vf, &fp);
  auto feats = fp.optimalTilingFeatures;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (feats & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (feats & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (feats & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (feats & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = vf;
  ci.extent = {w, h, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(gpu.device, &ci, nullptr, &handle), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(gpu.device, handle, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = gpu.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  check(vkAllocateMemory(gpu.device, &ai, nullptr, &memory), "vkAllocateMemory (image)");
  check(vkBindImageMemory(gpu.device, handle, memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = handle;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = vf;
  vi.subresourceRange = {aspect, 0, 1, 0, 1};
  check(vkCreateImageView(gpu.device, &vi, nullptr, &view), "vkCreateImageView");
  gpu.set_name(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(handle), name);
  // Every image lives in GENERAL layout for its whole life: the graph only needs memory
  // barriers between passes, never layout transitions.
  gpu.one_shot([&](VkCommandBuffer cb) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = handle;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.imageMemoryBarrierCount = 1;
    di.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cb, &di);
    if (depth) {
      VkClearDepthStencilValue z{1.0f, 0};
      vkCmdClearDepthStencilImage(cb, handle, VK_IMAGE_LAYOUT_GENERAL, &z, 1, &b.subresourceRange);
    } else {
      VkClearColorValue zero{};
      vkCmdClearColorImage(cb, handle, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &b.subresourceRange);
    }
    host_to_device_barrier(cb);
  });
}

VkImageObj::~VkImageObj() {
  vkDestroyImageView(gpu_.device, view, nullptr);
  vkDestroyImage(gpu_.device, handle, nullptr);
  vkFreeMemory(gpu_.device, memory, nullptr);
}

std::shared_ptr<Image> VkGpu::create_image(Format format, uint32_t w, uint32_t h, const std::string& name) {
  if (format == Format::buffer) throw GpuError(fmt::format("create_image '{}': format 'buffer' is not an image", name));
  if (w == 0 || h == 0) throw GpuError(fmt::format("create_image '{}': zero extent", name));
  return std::make_shared<VkImageObj>(*this, format, w, h, name);
}

void VkGpu::upload(const Image& dst_, const void* texels, uint64_t bytes) {
  auto& dst = static_cast<const VkImageObj&>(dst_);
  uint64_t expect = uint64_t(dst.width()) * dst.height() * format_bytes_per_texel(dst.format());
  if (bytes != expect) throw GpuError(fmt::format("upload image: expected {} bytes, got {}", expect, bytes));
  StagingUse use(*this, bytes);
  std::memcpy(use.s.mapped, texels, bytes);
  one_shot([&](VkCommandBuffer cb) {
    host_to_device_barrier(cb);
    VkBufferImageCopy r{};
    r.imageSubresource = {dst.aspect, 0, 0, 1};
    r.imageExtent = {dst.width(), dst.height(), 1};
    vkCmdCopyBufferToImage(cb, use.s.buffer, dst.handle, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
    host_to_device_barrier(cb);
  });
}

std::vector<uint8_t> VkGpu::download(const Image& src_) {
  auto& src = static_cast<const VkImageObj&>(src_);
  uint64_t bytes = uint64_t(src.width()) * src.height() * format_bytes_per_texel(src.format());
  StagingUse use(*this, bytes);
  one_shot([&](VkCommandBuffer cb) {
    host_to_device_barrier(cb);
    VkBufferImageCopy r{};
    r.imageSubresource = {src.aspect, 0, 0, 1};
    r.imageExtent = {src.width(), src.height(), 1};
    vkCmdCopyImageToBuffer(cb, src.handle, VK_IMAGE_LAYOUT_GENERAL, use.s.buffer, 1, &r);
    host_to_device_barrier(cb);
  });
  std::vector<uint8_t> out(bytes);
  std::memcpy(out.data(), use.s.mapped, bytes);
  return out;
}

}  // namespace vkimpl

std::unique_ptr<Gpu> Gpu::create(const GpuOptions& options) { return std::make_unique<vkimpl::VkGpu>(options); }

std::vector<DeviceInfo> Gpu::list_devices() {
  bool debug_utils = false;
  VkInstance inst = vkimpl::make_instance(false, &debug_utils);
  std::vector<DeviceInfo> out;
  try {
    for (auto& c : vkimpl::enumerate(inst)) out.push_back(c.info);
  } catch (...) {
    vkDestroyInstance(inst, nullptr);
    throw;
  }
  vkDestroyInstance(inst, nullptr);
  return out;
}

}  // namespace gib
