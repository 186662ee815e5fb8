// Shared by tests/test_codecs.cpp, tests/codecs_test.comp and tests/codecs_format_test.comp.
//
// codecs_test.comp, mode CODECS_TEST_MODE_PACKING: element i reads CodecsTestIn words w and
// writes CodecsTestOut: the encodes of the floats with bits w (rgb = w.xyz, halves of w.xy and
// w.zw), the device's own packHalf2x16, and the decodes of w.x as RGB9E5, w.y as R11G11B10F
// and w.z as two halves. Mode CODECS_TEST_MODE_GEOMETRY reads CodecsGeomIn and writes
// CodecsGeomOut (octahedral encode/decode, border mapping, SH2 basis and irradiance).
//
// codecs_format_test.comp: texel (x, y) of the width x height images fetches the E5B9G9R9 and
// B10G11R11 sampled images (CPU-packed bits uploaded) into CodecsFormatOut, and stores
// store_in[i].xyz through the B10G11R11 storage image (the device's own float conversion).
#ifndef GIB_CODECS_TEST_SHARED_H
#define GIB_CODECS_TEST_SHARED_H

#ifdef __cplusplus
#include <cstdint>
namespace gib::codecs_test {
using uint = uint32_t;
#endif

#define CODECS_TEST_WORKGROUP_SIZE 64
#define CODECS_TEST_BINDING_IN 0
#define CODECS_TEST_BINDING_OUT 1
#define CODECS_TEST_MODE_PACKING 0u
#define CODECS_TEST_MODE_GEOMETRY 1u

#define CODECS_FORMAT_BINDING_E5 0        // sampled E5B9G9R9
#define CODECS_FORMAT_BINDING_B10 1       // sampled B10G11R11
#define CODECS_FORMAT_BINDING_STORE 2     // storage B10G11R11
#define CODECS_FORMAT_BINDING_STORE_IN 3  // vec4 per texel
#define CODECS_FORMAT_BINDING_OUT 4       // CodecsFormatOut per texel
#define CODECS_FORMAT_BINDING_STORE16 5   // storage R16G16B16A16_SFLOAT (the same floats stored)
#define CODECS_FORMAT_WORKGROUP 8         // 8 x 8

struct CodecsTestIn {  // 16 bytes; also CodecsGeomIn's size is 32
  uint x, y, z, w;
};

struct CodecsTestOut {  // 72 bytes
  uint rgb9e5;          // gib_pack_rgb9e5(float bits x, y, z)
  uint r11g11b10;       // gib_pack_r11g11b10
  uint r11g11b10_rne;   // gib_pack_r11g11b10_rne
  uint half_xy;         // gib_pack_half2x16(x, y)
  uint half_zw;         // gib_pack_half2x16(z, w)
  uint native_half_xy;  // packHalf2x16(x, y): the device's conversion
  uint native_half_zw;
  uint rgb9e5_dither;   // gib_pack_rgb9e5_dither(float bits x, y, z; dither = bits w)
  float e5_r, e5_g, e5_b;     // gib_unpack_rgb9e5(x)
  float r11_r, r11_g, r11_b;  // gib_unpack_r11g11b10(y)
  float half_lo, half_hi;     // gib_unpack_half2x16(z)
  uint half_rtz_xy;           // gib_pack_half2x16_rtz(x, y)
  uint half_rtz_zw;           // gib_pack_half2x16_rtz(z, w)
};

struct CodecsGeomIn {  // 32 bytes
  float dx, dy, dz;    // direction to encode (normalised in the shader), SH normal
  float u, v;          // octahedral coordinate to decode
  int tx, ty;          // tile-local texel for gib_oct_border_source
  int interior;
};

struct CodecsGeomOut {  // 48 bytes
  float u, v;           // gib_oct_encode(normalize(d))
  float nx, ny, nz;     // gib_oct_decode(u, v)
  float irradiance;     // gib_sh2_irradiance(vec4(u, v, dx, dy) of the input, normalize(d))
  int sx, sy;           // gib_oct_border_source
  float b0, b1, b2, b3; // gib_sh2_basis(normalize(d))
};

struct CodecsTestPush {
  uint count;
  uint mode;
};

struct CodecsFormatOut {  // 32 bytes
  float e5_r, e5_g, e5_b;
  float b10_r, b10_g, b10_b;
  float pad0, pad1;
};

struct CodecsFormatPush {
  uint width, height;
};

#ifdef __cplusplus
static_assert(sizeof(CodecsTestOut) == 72 && sizeof(CodecsGeomIn) == 32 &&
              sizeof(CodecsGeomOut) == 48 && sizeof(CodecsFormatOut) == 32);
}  // namespace gib::codecs_test
#endif

#endif  // GIB_CODECS_TEST_SHARED_H
