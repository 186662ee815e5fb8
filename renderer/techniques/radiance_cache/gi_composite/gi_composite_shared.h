#ifndef GIB_GI_COMPOSITE_SHARED_H
#define GIB_GI_COMPOSITE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGiCompositeGroup, 8)
GIB_CONST(uint, kGiCompositeBindDirect, 8)         // direct_light (rgba32f)
GIB_CONST(uint, kGiCompositeBindAlbedo, 9)         // gbuffer_albedo (rgba16f)
GIB_CONST(uint, kGiCompositeBindHistory, 10)       // gi_history (this frame's; format: history_format)
GIB_CONST(uint, kGiCompositeBindHistoryDirect, 11) // gi_history_direct (same format)
GIB_CONST(uint, kGiCompositeBindExposure, 12)      // exposure (float[4], exposure_shared.h: word 0 P_now)
GIB_CONST(uint, kGiCompositeBindColor, 13)         // final_color (rgba32f)
GIB_CONST(uint, kGiCompositeBindIndirect, 14)      // indirect_diffuse (rgba32f)
GIB_CONST(uint, kGiCompositeBindDirectOut, 15)     // direct_radiance (rgba32f): the AOV contract's direct
GIB_CONST(uint, kGiCompositeExposureNow, 0)
GIB_SHARED_END
#endif
