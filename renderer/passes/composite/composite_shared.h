#ifndef GIB_COMPOSITE_SHARED_H
#define GIB_COMPOSITE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kCompositeGroup, 8)
GIB_CONST(uint, kCompositeBindDirect, 8)      // direct_light (rgba32f)
GIB_CONST(uint, kCompositeBindAlbedo, 9)      // gbuffer_albedo (rgba16f)
GIB_CONST(uint, kCompositeBindIrradiance, 10) // gi_irradiance (rgba32f, irradiance / pi)
GIB_CONST(uint, kCompositeBindColor, 11)      // final_color (rgba32f)
GIB_CONST(uint, kCompositeBindIndirect, 12)   // indirect_diffuse (rgba32f)
GIB_CONST(uint, kCompositeBindGiDirect, 13)   // gi_direct_irradiance (rgba32f, irradiance / pi)
GIB_CONST(uint, kCompositeBindDirectOut, 14)  // direct_radiance (rgba32f): the AOV contract's direct
GIB_SHARED_END
#endif
