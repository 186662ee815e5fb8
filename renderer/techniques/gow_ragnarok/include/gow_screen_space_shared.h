// Shared by C++ and GLSL: the push block of gow-ragnarok's screen-space passes (ssdo, ssgi) and
// the stream ids of their per-pixel rotations (gow_screen_space.glsl; CPU mirror:
// screen_space_pattern.h).
#ifndef GIB_GOW_SCREEN_SPACE_SHARED_H
#define GIB_GOW_SCREEN_SPACE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kSsGroup, 8)             // 8x8 threads
GIB_CONST(uint, kSsMaxDirections, 32)
GIB_CONST(uint, kSsMaxSteps, 64)
GIB_CONST(uint, kSsStreamSsdo, 0x55d0u)  // hash streams: ssdo and ssgi turn their patterns independently
GIB_CONST(uint, kSsStreamSsgi, 0x5591u)
struct ScreenSpacePush {
  vec4 params;   // x: march radius (m), y: thickness (m): a depth-buffer surface nearer than the
                 //   march point by more than this is taken to pass in front, not to block;
                 //   z, w: unused
  uvec4 counts;  // x: directions, y: steps per direction, z: 1 on (0: the pass's term is off),
                 //   w: 1 NaN guards
};
GIB_SHARED_END
#endif
