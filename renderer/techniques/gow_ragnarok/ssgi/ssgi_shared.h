#ifndef GIB_SSGI_SHARED_H
#define GIB_SSGI_SHARED_H
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kSsgiBindPosition, 8)   // gbuffer_position (rgba32f)
GIB_CONST(uint, kSsgiBindNormal, 9)     // gbuffer_normal (rgba16f)
GIB_CONST(uint, kSsgiBindAlbedo, 10)    // gbuffer_albedo (rgba16f)
GIB_CONST(uint, kSsgiBindEmissive, 11)  // gbuffer_emissive (rgba16f)
GIB_CONST(uint, kSsgiBindDirect, 12)    // direct_light (rgba32f)
GIB_CONST(uint, kSsgiBindLocal, 13)     // ssdo_local_light (rgba32f; direct_light again when absent)
GIB_CONST(uint, kSsgiBindOutDirect, 14)    // gow_direct: direct_light + ssdo_local_light
GIB_CONST(uint, kSsgiBindOutIndirect, 15)  // ssgi_indirect
GIB_CONST(uint, kSsgiBindOutRadiance, 16)  // gow_radiance
GIB_CONST(uint, kSsgiSpecLocal, 0)         // 1: ssdo_local_light is bound and added
GIB_SHARED_END
#endif
