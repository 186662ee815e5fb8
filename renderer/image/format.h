// Storage formats of images and buffers: below both the Vulkan layer (which maps them to
// VkFormat) and the render graph (whose slots declare them).
#pragma once
#include <cstdint>

namespace gib {

enum class Format : uint32_t {
  r32_uint, rg32_uint, rgba32_uint, r32_float, rg32_float, rgba32_float,
  rg16_float, rgba16_float, rgba16_uint, rgba8_unorm, b10g11r11_float, e5b9g9r9_float,
  d32_float, buffer
};
const char* format_name(Format f);
uint32_t format_bytes_per_texel(Format f);  // 0 for buffer

}  // namespace gib
