#ifndef GIB_DIRECT_AOV_SHARED_H
#define GIB_DIRECT_AOV_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kDirectAovGroup, 8)       // 8x8 pixels a workgroup
GIB_CONST(uint, kDirectAovBindDirect, 8)  // direct_light (rgba32f)
GIB_CONST(uint, kDirectAovBindLocal, 9)   // ssdo_local_light (rgba16f, sampled); direct_light, unread, without local lights
GIB_CONST(uint, kDirectAovBindOut, 10)    // out: gow_direct (rgba32f)
GIB_CONST(uint, kDirectAovSpecLocal, 0)   // 1: the scene has unshadowed local lights
GIB_SHARED_END
#endif
