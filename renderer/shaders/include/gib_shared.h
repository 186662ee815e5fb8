// Prelude for headers included by both C++ and GLSL (the *_shared.h files): GLSL type names
// in C++, and std430/std140-compatible plain structs, so bindings, push constants and
// workgroup sizes cannot drift between the two sides.
#ifndef GIB_SHARED_H
#define GIB_SHARED_H
#ifdef __cplusplus
#include <cstdint>
namespace gib::glsl {
using uint = uint32_t;
struct vec2 { float x, y; };
struct vec4 { float x, y, z, w; };
struct uvec2 { uint32_t x, y; };
struct uvec4 { uint32_t x, y, z, w; };
struct ivec4 { int32_t x, y, z, w; };
struct mat4 { float m[16]; };  // column-major, as GLSL
}  // namespace gib::glsl
#define GIB_SHARED_BEGIN namespace gib::glsl {
#define GIB_SHARED_END }
#define GIB_CONST(type, name, value) inline constexpr type name = value;
#else
#define GIB_SHARED_BEGIN
#define GIB_SHARED_END
#define GIB_CONST(type, name, value) const type name = value;
#endif
#endif
