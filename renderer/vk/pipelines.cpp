// Compute and graphics pipelines from embedded SPIR-V, cached by description.
#include <algorithm>
#include <fmt/format.h>

#include "renderer/vk/internal.h"
#include "device_spec_shared.h"

namespace gib {

std::array<uint32_t, 3> spirv_local_size(std::span<const uint32_t> words) {
  constexpr uint32_t kMagic = 0x07230203, kOpExecutionMode = 16, kLocalSize = 17;
  if (words.size() < 5 || words[0] != kMagic) return {0, 0, 0};
  for (size_t i = 5; i < words.size();) {
    const uint32_t count = words[i] >> 16, op = words[i] & 0xffffu;
    if (count == 0 || i + count > words.size()) break;
    // OpExecutionMode %entry LocalSize x y z
    if (op == kOpExecutionMode && count >= 6 && words[i + 2] == kLocalSize)
      return {words[i + 3], words[i + 4], words[i + 5]};
    i += count;
  }
  return {0, 0, 0};
}

}  // namespace gib

namespace gib::vkimpl {
namespace {

VkDescriptorType descriptor_type(DescriptorKind k) {
  switch (k) {
    case DescriptorKind::storage_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case DescriptorKind::uniform_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case DescriptorKind::storage_image: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case DescriptorKind::sampled_image: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

VkShaderModule load_module(VkDevice device, const std::string& name) {
  auto& reg = shader_registry();
  auto it = reg.find(name);
  if (it == reg.end()) throw GpuError(fmt::format("shader '{}': not embedded in this binary (unknown kernel name)", name));
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = it->second.size() * sizeof(uint32_t);
  ci.pCode = it->second.data();
  VkShaderModule m = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

void make_layout(VkGpu& gpu, VkPipelineObj& p, VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bs;
  for (auto& b : p.bindings) {
    VkDescriptorSetLayoutBinding lb{};
    lb.binding = b.binding;
    lb.descriptorType = descriptor_type(b.kind);
    lb.descriptorCount = 1;
    lb.stageFlags = stages;
    bs.push_back(lb);
  }
  VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  dl.bindingCount = static_cast<uint32_t>(bs.size());
  dl.pBindings = bs.data();
  check(vkCreateDescriptorSetLayout(gpu.device, &dl, nullptr, &p.set_layout), "vkCreateDescriptorSetLayout");
  VkPushConstantRange range{stages, 0, p.push_bytes};
  VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pl.setLayoutCount = 1;
  pl.pSetLayouts = &p.set_layout;
  pl.pushConstantRangeCount = p.push_bytes ? 1 : 0;
  pl.pPushConstantRanges = &range;
  check(vkCreatePipelineLayout(gpu.device, &pl, nullptr, &p.layout), "vkCreatePipelineLayout");
}

// Vulkan's two-call enumeration: the count, then the items (each starting as `init`, which
// carries its sType).
template <typename T, typename Call>
std::vector<T> vk_enumerate(const T& init, Call call, const char* what) {
  uint32_t n = 0;
  check(call(&n, nullptr), what);
  std::vector<T> items(n, init);
  check(call(&n, items.data()), what);
  items.resize(n);
  return items;
}

// The driver's statistics of every executable of a pipeline created with
// VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR.
std::vector<PipelineStatistic> read_statistics(const VkGpu& gpu, VkPipeline pipeline) {
  std::vector<PipelineStatistic> out;
  VkPipelineInfoKHR pi{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pi.pipeline = pipeline;
  const auto execs = vk_enumerate<VkPipelineExecutablePropertiesKHR>(
      {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR},
      [&](uint32_t* n, VkPipelineExecutablePropertiesKHR* p) { return gpu.executable_properties_fn(gpu.device, &pi, n, p); },
      "vkGetPipelineExecutablePropertiesKHR");
  for (uint32_t e = 0; e < execs.size(); ++e) {
    VkPipelineExecutableInfoKHR ei{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    ei.pipeline = pipeline;
    ei.executableIndex = e;
    const auto stats = vk_enumerate<VkPipelineExecutableStatisticKHR>(
        {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR},
        [&](uint32_t* n, VkPipelineExecutableStatisticKHR* p) { return gpu.executable_statistics_fn(gpu.device, &ei, n, p); },
        "vkGetPipelineExecutableStatisticsKHR");
    for (const VkPipelineExecutableStatisticKHR& s : stats) {
      double v = 0;
      switch (s.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: v = s.value.b32 ? 1 : 0; break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: v = double(s.value.i64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: v = double(s.value.u64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: v = s.value.f64; break;
        default: continue;
      }
      out.push_back({execs[e].name, s.name, s.description, v});
    }
  }
  return out;
}

std::string binding_key(const std::vector<BindingDecl>& bs) {
  std::string k;
  for (auto& b : bs) k += fmt::format("{}:{},", b.binding, static_cast<uint32_t>(b.kind));
  return k;
}

}  // namespace

VkPipelineObj::~VkPipelineObj() {
  if (!device) return;
  vkDestroyPipeline(device, pipeline, nullptr);
  vkDestroyPipelineLayout(device, layout, nullptr);
  vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
}

std::shared_ptr<Pipeline> VkGpu::compute_pipeline(const ComputePipelineDesc& desc) {
  std::vector<SpecConstant> spec_constants = desc.spec_constants;
  if (std::none_of(spec_constants.begin(), spec_constants.end(),
                   [](const SpecConstant& s) { return s.id == glsl::kGibSpecNativeHalfRne; }))
    spec_constants.push_back({glsl::kGibSpecNativeHalfRne, native_half_rne_});
  std::string key = fmt::format("C|{}|{}|{}|", desc.shader, binding_key(desc.bindings), desc.push_constant_bytes);
  for (auto& s : spec_constants) key += fmt::format("{}={},", s.id, s.value);
  if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;

  auto p = std::make_shared<VkPipelineObj>();
  p->name_ = desc.shader;
  p->device = device;
  p->bindings = desc.bindings;
  p->push_bytes = desc.push_constant_bytes;
  make_layout(*this, *p, VK_SHADER_STAGE_COMPUTE_BIT);
  VkShaderModule module = load_module(device, desc.shader);
  p->local_size_ = spirv_local_size(shader_registry().at(desc.shader));
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (size_t i = 0; i < spec_constants.size(); ++i) {
    entries.push_back({spec_constants[i].id, static_cast<uint32_t>(i * 4), 4});
    values.push_back(spec_constants[i].value);
  }
  VkSpecializationInfo spec{static_cast<uint32_t>(entries.size()), entries.data(), values.size() * 4, values.data()};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = entries.empty() ? nullptr : &spec;
  ci.layout = p->layout;
  if (info_.pipeline_statistics) ci.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  VkResult r = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &p->pipeline);
  vkDestroyShaderModule(device, module, nullptr);
  check(r, "vkCreateComputePipelines");
  if (info_.pipeline_statistics) p->statistics_ = read_statistics(*this, p->pipeline);
  set_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(p->pipeline), desc.shader);
  pipelines_[key] = p;
  return p;
}

std::shared_ptr<Pipeline> VkGpu::graphics_pipeline(const GraphicsPipelineDesc& desc) {
  std::string key = fmt::format("G|{}|{}|{}|{}|{}|", desc.vertex_shader, desc.fragment_shader, binding_key(desc.bindings),
                                desc.push_constant_bytes, desc.depth);
  for (auto f : desc.color_formats) key += format_name(f);
  if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;

  auto p = std::make_shared<VkPipelineObj>();
  p->name_ = desc.vertex_shader + "+" + desc.fragment_shader;
  p->device = device;
  p->bindings = desc.bindings;
  p->push_bytes = desc.push_constant_bytes;
  p->bind_point = VK_PIPELINE_BIND_POINT_GRAPHICS;
  make_layout(*this, *p, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  VkShaderModule vs = load_module(device, desc.vertex_shader);
  VkShaderModule fs = load_module(device, desc.fragment_shader);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";
  VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;  // every surface is double-sided, as in the tracer
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.depth;
  ds.depthWriteEnable = desc.depth;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.color_formats.size());
  for (auto& b : blends) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = static_cast<uint32_t>(blends.size());
  cb.pAttachments = blends.data();
  VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dyn;
  std::vector<VkFormat> colors;
  for (auto f : desc.color_formats) colors.push_back(to_vk(f));
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
  ri.pColorAttachmentFormats = colors.data();
  ri.depthAttachmentFormat = desc.depth ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_UNDEFINED;
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &ri;
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vin;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = p->layout;
  VkResult r = vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &p->pipeline);
  vkDestroyShaderModule(device, vs, nullptr);
  vkDestroyShaderModule(device, fs, nullptr);
  check(r, "vkCreateGraphicsPipelines");
  pipelines_[key] = p;
  return p;
}

}  // namespace gib::vkimpl
