#ifndef GIB_REFLECTIONS_RT_CUBEMAP_SHARED_H
#define GIB_REFLECTIONS_RT_CUBEMAP_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kReflTraceGroup, 8)
GIB_CONST(uint, kReflTraceBindVbuffer, 8)
GIB_CONST(uint, kReflTraceBindPosition, 9)
GIB_CONST(uint, kReflTraceBindNormal, 10)
GIB_CONST(uint, kReflTraceBindAlbedo, 11)
GIB_CONST(uint, kReflTraceBindScreen, 12)   // direct_light: the lit screen
GIB_CONST(uint, kReflTraceBindCubemap, 13)  // reflection_cubemap (sums and counts)
GIB_CONST(uint, kReflTraceBindOut, 14)      // reflection_trace, half resolution
GIB_CONST(uint, kReflTraceBindStats, 15)    // reflection_stats
GIB_CONST(uint, kReflTraceSpecMode, 0)      // ReflectionMode: 0 cube map alone, 1 ray-traced cube maps
// reflection_stats words: glossy samples, then the seed's colours of where a sample's colour came
// from: screen-space hit (cyan), BVH hit read from the screen (purple), BVH hit read from the cube
// map (yellow); then rays that left the scene (sky) and rays masked by the lobe (weight 0).
GIB_CONST(uint, kReflStatSamples, 0)
GIB_CONST(uint, kReflStatScreen, 1)
GIB_CONST(uint, kReflStatBvhScreen, 2)
GIB_CONST(uint, kReflStatCubemap, 3)
GIB_CONST(uint, kReflStatSky, 4)
GIB_CONST(uint, kReflStatMasked, 5)
GIB_CONST(uint, kReflStatWords, 8)
struct ReflTracePush {
  uint frame;
  uint cubemap_size;
  uint ssr_steps;
  float ssr_thickness;
  float distance;
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
