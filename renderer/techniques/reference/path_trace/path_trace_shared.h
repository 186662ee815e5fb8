#ifndef GIB_PATH_TRACE_SHARED_H
#define GIB_PATH_TRACE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPathTraceGroup, 8)
// Running sums (rgb) and sample count (a) of each AOV, persistent across frames.
GIB_CONST(uint, kPathTraceBindRadiance, 8)
GIB_CONST(uint, kPathTraceBindDirect, 9)
GIB_CONST(uint, kPathTraceBindIndirect, 10)
GIB_CONST(uint, kPathTraceBindReflection, 11)
GIB_CONST(uint, kPathTraceSpecSun, 0)
GIB_CONST(uint, kPathTraceSpecLocal, 1)
GIB_CONST(uint, kPathTraceSpecAlpha, 2)
struct PathTracePush {
  uint spp;          // samples added this frame
  uint max_bounces;  // path vertices after the camera hit
  uint sample_base;  // samples accumulated before this frame (decorrelates frames)
  uint nan_guards;   // 1: a sample with a non-finite contribution is not accumulated (nor counted)
  uint inject_nan;   // 1: the first sample of pixel (inject_x, inject_y) is NaN this frame (debug)
  uint inject_x, inject_y;
  uint glossy_masking;  // 1: the glossy lobe's Smith masking; 0: none (G = 1), a negative control
};
GIB_SHARED_END
#endif
