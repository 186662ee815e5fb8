// The visibility-buffer encoding, shared by its writer (visibility) and every reader:
// R32G32_UINT, x = triangle id + 1 (0: nothing hit, the sky), y = instance id.
#ifndef GIB_VBUFFER_SHARED_H
#define GIB_VBUFFER_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kVisibilityNone, 0)
GIB_SHARED_END
#endif
