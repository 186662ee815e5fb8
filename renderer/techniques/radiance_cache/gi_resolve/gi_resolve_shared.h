#ifndef GIB_GI_RESOLVE_SHARED_H
#define GIB_GI_RESOLVE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGiResolveGroup, 8)
GIB_CONST(uint, kGiResolveBindHistory, 8)            // gi_history (this frame's; format: history_format)
GIB_CONST(uint, kGiResolveBindHistoryDirect, 9)      // gi_history_direct (same format)
GIB_CONST(uint, kGiResolveBindExposure, 10)          // exposure (float[4], exposure_shared.h: word 0 P_now)
GIB_CONST(uint, kGiResolveBindIrradiance, 11)        // gi_irradiance (rgba32f: irradiance / pi)
GIB_CONST(uint, kGiResolveBindDirectIrradiance, 12)  // gi_direct_irradiance (rgba32f: irradiance / pi)
GIB_CONST(uint, kGiResolveExposureNow, 0)
GIB_SHARED_END
#endif
