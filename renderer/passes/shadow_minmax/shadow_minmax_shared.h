#ifndef GIB_SHADOW_MINMAX_SHARED_H
#define GIB_SHADOW_MINMAX_SHARED_H
#include "shadow_cascades_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kMinMaxBindTiles, 13)  // rg32f: min, max per tile (shadow_minmax_tiles); the dilation's source
GIB_SHARED_END
#endif
