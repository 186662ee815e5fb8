// Names and texel sizes of the storage formats.
#include "renderer/image/format.h"

namespace gib {

const char* format_name(Format f) {
  switch (f) {
    case Format::r32_uint: return "r32_uint";
    case Format::rg32_uint: return "rg32_uint";
    case Format::rgba32_uint: return "rgba32_uint";
    case Format::r32_float: return "r32_float";
    case Format::rg32_float: return "rg32_float";
    case Format::rgba32_float: return "rgba32_float";
    case Format::rg16_float: return "rg16_float";
    case Format::rgba16_float: return "rgba16_float";
    case Format::rgba16_uint: return "rgba16_uint";
    case Format::rgba8_unorm: return "rgba8_unorm";
    case Format::b10g11r11_float: return "b10g11r11_float";
    case Format::e5b9g9r9_float: return "e5b9g9r9_float";
    case Format::d32_float: return "d32_float";
    case Format::buffer: return "buffer";
  }
  return "?";
}

uint32_t format_bytes_per_texel(Format f) {
  switch (f) {
    case Format::r32_uint: case Format::r32_float: case Format::rg16_float:
    case Format::rgba8_unorm: case Format::b10g11r11_float: case Format::e5b9g9r9_float:
    case Format::d32_float:
      return 4;
    case Format::rg32_uint: case Format::rg32_float: case Format::rgba16_float: case Format::rgba16_uint: return 8;
    case Format::rgba32_uint: case Format::rgba32_float: return 16;
    case Format::buffer: return 0;
  }
  return 0;
}

}  // namespace gib
