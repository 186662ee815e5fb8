// Command recording: descriptor sets per bind, dispatches, dynamic rendering, barriers,
// timestamps, debug labels; submission with timestamp readback.
#include <fmt/format.h>

#include <cstring>

#include "renderer/vk/internal.h"

namespace gib::vkimpl {
namespace {

VkPipelineStageFlags2 stages_of(uint32_t mask) {
  VkPipelineStageFlags2 s = 0;
  if (mask & kStageCompute) s |= VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
  if (mask & kStageGraphics)
    s |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
         VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  if (mask & kStageTransfer) s |= VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  if (mask & kStageHost) s |= VK_PIPELINE_STAGE_2_HOST_BIT;
  return s ? s : VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
}

}  // namespace

VkCmd::VkCmd(VkGpu& g, VkCommandPool p, uint32_t qcount) : gpu(g), pool(p), query_count(qcount) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(gpu.device, &ai, &cb), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
  if (query_count) {
    if (gpu.info().timestamp_period_ns == 0) throw GpuError("vulkan: the queue has no timestamp support");
    queries = gpu.take_query_pool(query_count);
    vkCmdResetQueryPool(cb, queries, 0, query_count);
  }
}

VkCmd::~VkCmd() {
  for (auto dp : descriptor_pools_) gpu.keep_descriptor_pool(dp);
  if (queries) gpu.keep_query_pool(queries, query_count);
  vkFreeCommandBuffers(gpu.device, pool, 1, &cb);
}

VkDescriptorPool VkCmd::descriptor_pool() {
  if (descriptor_pools_.empty() || sets_in_pool_ == kSetsPerPool) {
    descriptor_pools_.push_back(gpu.take_descriptor_pool());
    sets_in_pool_ = 0;
  }
  ++sets_in_pool_;
  return descriptor_pools_.back();
}

void VkCmd::bind(const Pipeline& pipeline_, std::span<const Bind> binds, const void* push, uint32_t push_bytes) {
  auto& p = static_cast<const VkPipelineObj&>(pipeline_);
  if (push_bytes != p.push_bytes)
    throw GpuError(fmt::format("bind '{}': push constants are {} bytes, pipeline expects {}", p.name(), push_bytes, p.push_bytes));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descriptor_pool();
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &p.set_layout;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(gpu.device, &ai, &set), "vkAllocateDescriptorSets");
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> bufs(p.bindings.size());
  std::vector<VkDescriptorImageInfo> imgs(p.bindings.size());
  for (size_t i = 0; i < p.bindings.size(); ++i) {
    const auto& decl = p.bindings[i];
    const Bind* b = nullptr;
    for (auto& x : binds)
      if (x.binding == decl.binding) b = &x;
    if (!b) throw GpuError(fmt::format("bind '{}': binding {} has no resource", p.name(), decl.binding));
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = decl.binding;
    w.descriptorCount = 1;
    switch (decl.kind) {
      case DescriptorKind::storage_buffer:
      case DescriptorKind::uniform_buffer: {
        if (!b->buffer) throw GpuError(fmt::format("bind '{}': binding {} expects a buffer", p.name(), decl.binding));
        bufs[i] = {static_cast<const VkBufferObj*>(b->buffer)->handle, 0, VK_WHOLE_SIZE};
        w.descriptorType = decl.kind == DescriptorKind::storage_buffer ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                                       : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        w.pBufferInfo = &bufs[i];
        break;
      }
      case DescriptorKind::storage_image:
      case DescriptorKind::sampled_image: {
        if (!b->image) throw GpuError(fmt::format("bind '{}': binding {} expects an image", p.name(), decl.binding));
        imgs[i] = {gpu.nearest_sampler, static_cast<const VkImageObj*>(b->image)->view, VK_IMAGE_LAYOUT_GENERAL};
        w.descriptorType = decl.kind == DescriptorKind::storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                                      : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w.pImageInfo = &imgs[i];
        break;
      }
    }
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(gpu.device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  vkCmdBindPipeline(cb, p.bind_point, p.pipeline);
  vkCmdBindDescriptorSets(cb, p.bind_point, p.layout, 0, 1, &set, 0, nullptr);
  if (push_bytes) {
    VkShaderStageFlags stages = p.bind_point == VK_PIPELINE_BIND_POINT_COMPUTE
                                    ? VK_SHADER_STAGE_COMPUTE_BIT
                                    : (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    vkCmdPushConstants(cb, p.layout, stages, 0, push_bytes, push);
  }
}

void VkCmd::dispatch(uint32_t x, uint32_t y, uint32_t z) {
  if (x && y && z) vkCmdDispatch(cb, x, y, z);
}

void VkCmd::dispatch_indirect(const Buffer& args, uint64_t offset) {
  vkCmdDispatchIndirect(cb, static_cast<const VkBufferObj&>(args).handle, offset);
}

void VkCmd::begin_rendering(std::span<const Image* const> colors, const Image* depth, const float clear_color[4]) {
  std::vector<VkRenderingAttachmentInfo> atts;
  uint32_t w = 0, h = 0;
  for (auto* c : colors) {
    auto* img = static_cast<const VkImageObj*>(c);
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = img->view;
    a.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (is_uint_format(img->format()))
      for (int i = 0; i < 4; ++i) a.clearValue.color.uint32[i] = static_cast<uint32_t>(clear_color[i]);
    else
      std::memcpy(a.clearValue.color.float32, clear_color, sizeof(float) * 4);
    atts.push_back(a);
    w = img->width();
    h = img->height();
  }
  VkRenderingAttachmentInfo da{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  if (depth) {
    auto* img = static_cast<const VkImageObj*>(depth);
    da.imageView = img->view;
    da.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
    da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    da.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    da.clearValue.depthStencil = {1.0f, 0};
    w = img->width();
    h = img->height();
  }
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {w, h}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = static_cast<uint32_t>(atts.size());
  ri.pColorAttachments = atts.data();
  ri.pDepthAttachment = depth ? &da : nullptr;
  vkCmdBeginRendering(cb, &ri);
  VkViewport vp{0, 0, static_cast<float>(w), static_cast<float>(h), 0.0f, 1.0f};
  VkRect2D sc{{0, 0}, {w, h}};
  vkCmdSetViewport(cb, 0, 1, &vp);
  vkCmdSetScissor(cb, 0, 1, &sc);
}

void VkCmd::set_viewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  VkViewport vp{static_cast<float>(x), static_cast<float>(y), static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
  VkRect2D sc{{static_cast<int32_t>(x), static_cast<int32_t>(y)}, {width, height}};
  vkCmdSetViewport(cb, 0, 1, &vp);
  vkCmdSetScissor(cb, 0, 1, &sc);
}

void VkCmd::draw(uint32_t vertex_count) {
  if (vertex_count) vkCmdDraw(cb, vertex_count, 1, 0, 0);
}
void VkCmd::end_rendering() { vkCmdEndRendering(cb); }

void VkCmd::barrier(uint32_t src_stages, uint32_t dst_stages) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = stages_of(src_stages);
  mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  mb.dstStageMask = stages_of(dst_stages);
  mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cb, &di);
}

void VkCmd::fill(const Buffer& buffer, uint32_t value) {
  vkCmdFillBuffer(cb, static_cast<const VkBufferObj&>(buffer).handle, 0, VK_WHOLE_SIZE, value);
}

void VkCmd::update(const Buffer& buffer, const void* data, uint32_t bytes) {
  if (bytes == 0 || bytes > 65536 || bytes % 4 || bytes > buffer.size())
    throw GpuError(fmt::format("update: expected 4 to 65536 bytes, a multiple of 4, within the buffer's {}; got {}",
                               buffer.size(), bytes));
  vkCmdUpdateBuffer(cb, static_cast<const VkBufferObj&>(buffer).handle, 0, bytes, data);
}

void VkCmd::clear(const Image& image, const float value[4]) {
  auto& img = static_cast<const VkImageObj&>(image);
  VkImageSubresourceRange range{img.aspect, 0, 1, 0, 1};
  if (img.format() == Format::d32_float) {
    VkClearDepthStencilValue z{value[0], 0};
    vkCmdClearDepthStencilImage(cb, img.handle, VK_IMAGE_LAYOUT_GENERAL, &z, 1, &range);
    return;
  }
  VkClearColorValue c{};
  if (is_uint_format(img.format()))
    for (int i = 0; i < 4; ++i) c.uint32[i] = static_cast<uint32_t>(value[i]);
  else
    std::memcpy(c.float32, value, sizeof(float) * 4);
  vkCmdClearColorImage(cb, img.handle, VK_IMAGE_LAYOUT_GENERAL, &c, 1, &range);
}

void VkCmd::copy(const Image& src_, const Image& dst_) {
  auto& src = static_cast<const VkImageObj&>(src_);
  auto& dst = static_cast<const VkImageObj&>(dst_);
  if (src.format() != dst.format() || src.width() != dst.width() || src.height() != dst.height())
    throw GpuError("copy: images differ in format or extent");
  VkImageCopy r{};
  r.srcSubresource = {src.aspect, 0, 0, 1};
  r.dstSubresource = {dst.aspect, 0, 0, 1};
  r.extent = {src.width(), src.height(), 1};
  vkCmdCopyImage(cb, src.handle, VK_IMAGE_LAYOUT_GENERAL, dst.handle, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
}

void VkCmd::copy(const Buffer& src_, const Buffer& dst_) {
  auto& src = static_cast<const VkBufferObj&>(src_);
  auto& dst = static_cast<const VkBufferObj&>(dst_);
  if (src.size() != dst.size()) throw GpuError("copy: buffers differ in size");
  VkBufferCopy r{0, 0, src.size()};
  vkCmdCopyBuffer(cb, src.handle, dst.handle, 1, &r);
}

void VkCmd::timestamp(uint32_t query) {
  if (query >= query_count) throw GpuError(fmt::format("timestamp: query {} out of range ({})", query, query_count));
  vkCmdWriteTimestamp2(cb, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, query);
  queries_written = std::max(queries_written, query + 1);
}

void VkCmd::begin_label(const std::string& name) {
  if (!gpu.begin_label_fn) return;
  VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  l.pLabelName = name.c_str();
  gpu.begin_label_fn(cb, &l);
}
void VkCmd::end_label() {
  if (gpu.end_label_fn) gpu.end_label_fn(cb);
}

std::unique_ptr<Cmd> VkGpu::begin(uint32_t query_count) {
  return std::make_unique<VkCmd>(*this, command_pool(), query_count);
}

std::vector<double> VkGpu::submit(std::unique_ptr<Cmd> cmd_) {
  auto* cmd = static_cast<VkCmd*>(cmd_.get());
  check(vkEndCommandBuffer(cmd->cb), "vkEndCommandBuffer");
  submit_and_wait(cmd->cb);
  std::vector<double> ns;
  if (cmd->queries_written) {
    std::vector<uint64_t> ticks(cmd->queries_written);
    check(vkGetQueryPoolResults(device, cmd->queries, 0, cmd->queries_written, ticks.size() * 8, ticks.data(), 8,
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    uint64_t mask = timestamp_valid_bits >= 64 ? ~0ull : ((1ull << timestamp_valid_bits) - 1);
    for (auto t : ticks) ns.push_back(static_cast<double>(t & mask) * info().timestamp_period_ns);
  }
  return ns;
}

}  // namespace gib::vkimpl
