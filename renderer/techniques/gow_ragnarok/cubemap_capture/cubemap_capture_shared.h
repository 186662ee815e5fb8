#ifndef GIB_CUBEMAP_CAPTURE_SHARED_H
#define GIB_CUBEMAP_CAPTURE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kCubemapCaptureGroup, 8)
GIB_CONST(uint, kCubemapCaptureBindSum, 8)  // rgba32f 6N x N: radiance sums (rgb), sample count (a)
struct CubemapCapturePush {
  uint size;       // N, texels per face side
  uint bounces;    // path vertices after the capture ray's hit
  uint frame;      // decorrelates frames
  uint nan_guards; // 1: a non-finite sample is dropped
};
GIB_SHARED_END
#endif
