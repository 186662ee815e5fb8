// gi_history.glsl (owner: gi_upscale): this frame's gi_history / gi_history_direct read back by
// the passes after gi_upscale. GI_HISTORY_FORMAT as gi_upscale.glsl (0 RGB9E5 in r32ui,
// 1 rgba16f, 2 r11f_g11f_b10f, 3 rgba32f). gi_upscale quantises each value before its store, so
// the image holds it exactly and LOAD returns the very value gi_upscale's STORE returned.
//   GI_HISTORY_READER(NAME, BIND, LOAD): declares the readonly image NAME at binding BIND and
//   vec3 LOAD(ivec2 p).
#ifndef GIB_GI_HISTORY_GLSL
#define GIB_GI_HISTORY_GLSL
#include "packing.glsl"
#if GI_HISTORY_FORMAT == 0
#define GI_HISTORY_READER(NAME, BIND, LOAD)                                    \
  layout(set = 0, binding = BIND, r32ui) uniform readonly uimage2D NAME;       \
  vec3 LOAD(ivec2 p) { return gib_unpack_rgb9e5(imageLoad(NAME, p).x); }
#elif GI_HISTORY_FORMAT == 1
#define GI_HISTORY_READER(NAME, BIND, LOAD)                                    \
  layout(set = 0, binding = BIND, rgba16f) uniform readonly image2D NAME;      \
  vec3 LOAD(ivec2 p) { return imageLoad(NAME, p).rgb; }
#elif GI_HISTORY_FORMAT == 2
#define GI_HISTORY_READER(NAME, BIND, LOAD)                                    \
  layout(set = 0, binding = BIND, r11f_g11f_b10f) uniform readonly image2D NAME; \
  vec3 LOAD(ivec2 p) { return imageLoad(NAME, p).rgb; }
#else
#define GI_HISTORY_READER(NAME, BIND, LOAD)                                    \
  layout(set = 0, binding = BIND, rgba32f) uniform readonly image2D NAME;      \
  vec3 LOAD(ivec2 p) { return imageLoad(NAME, p).rgb; }
#endif
#endif
