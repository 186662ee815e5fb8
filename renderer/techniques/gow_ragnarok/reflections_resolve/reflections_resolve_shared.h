#ifndef GIB_REFLECTIONS_RESOLVE_SHARED_H
#define GIB_REFLECTIONS_RESOLVE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kReflResolveGroup, 8)
GIB_CONST(uint, kReflResolveBindTrace, 8)     // reflection_trace (half resolution)
GIB_CONST(uint, kReflResolveBindPosition, 9)  // gbuffer_position
GIB_CONST(uint, kReflResolveBindHistory, 10)  // reflection, last frame
GIB_CONST(uint, kReflResolveBindOut, 11)      // reflection: rgb, a = frames averaged
struct ReflResolvePush {
  float history;  // frames averaged at most
  uint has_history;
  uint nan_guards;
  uint pad;
};
GIB_SHARED_END
#endif
