#ifndef GIB_SSDO_SHARED_H
#define GIB_SSDO_SHARED_H
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kSsdoBindPosition, 8)  // gbuffer_position (rgba32f)
GIB_CONST(uint, kSsdoBindNormal, 9)    // gbuffer_normal (rgba16f)
GIB_CONST(uint, kSsdoBindAlbedo, 10)   // gbuffer_albedo (rgba16f)
GIB_CONST(uint, kSsdoBindLight, 11)    // out: rgba32f local-light radiance through the SSDO cone
GIB_CONST(uint, kSsdoBindCone, 12)     // out: rgba16f bent normal xyz, visible fraction w
GIB_SHARED_END
#endif
