// exposure <-> C++: bindings, push constants and the layout of the `exposure` buffer that
// final_gather and gi_upscale read (see exposure.h for the computation).
#ifndef GIB_EXPOSURE_SHARED_H
#define GIB_EXPOSURE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kExposureGroup, 256)         // threads per workgroup, both stages
// Stage 0: up to kExposurePartials workgroups, grid-stride over the pixels, each writes its
// partial (sum of log2 Y, lit count) to words kExposurePartialFirst + 2g, + 2g + 1; stage 1:
// one workgroup adds the partials in a fixed order and writes P. (One workgroup for the whole
// image took 1.3 ms at 1600x900 on an H100: it runs on one SM.)
GIB_CONST(uint, kExposurePartials, 128)
// Pixels read: (x, y) with x and y multiples of kExposureStride (1/16 of the image): the
// log-average needs no more, and reading every pixel cost 0.047 ms at 1600x900 on an H100.
GIB_CONST(uint, kExposureStride, 4)
GIB_CONST(uint, kExposureBindDirect, 8)      // direct_light (rgba32f), this frame
GIB_CONST(uint, kExposureBindPrevColor, 9)   // last frame's final_color (rgba32f)
GIB_CONST(uint, kExposureBindOut, 10)        // exposure (persistent buffer, float[kExposureWords])
// Words of the exposure buffer: P this frame, P last frame (== P this frame on the first
// frame), the log-average luminance of the lit pixels (0 when none) and their count (a float).
GIB_CONST(uint, kExposureNow, 0)
GIB_CONST(uint, kExposurePrev, 1)
GIB_CONST(uint, kExposureAverage, 2)
GIB_CONST(uint, kExposureLitPixels, 3)
GIB_CONST(uint, kExposurePartialFirst, 4)
GIB_CONST(uint, kExposureWords, 260)          // 4 + 2 * kExposurePartials
// A pixel is lit when its luminance exceeds this (and is finite); P = 2^-mean(log2 Y) clamped
// to [2^-kExposureMaxLog2, 2^kExposureMaxLog2]; 1 when no pixel is lit.
GIB_CONST(float, kExposureMinLuminance, 1e-10)
GIB_CONST(float, kExposureMaxLog2, 20.0)

struct ExposurePush {
  uint enabled;     // 0: P = 1 every frame (pre_exposure off)
  uint prev_valid;  // 0 on the first frame: last frame's final_color was never written
  uint stage;       // 0: partial sums, 1: P from the partials
  uint partials;    // workgroups of stage 0 (<= kExposurePartials)
};
GIB_SHARED_END
#endif
