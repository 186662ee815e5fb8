#ifndef GIB_PATH_TRACE_RESOLVE_SHARED_H
#define GIB_PATH_TRACE_RESOLVE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kResolveGroup, 8)
GIB_CONST(uint, kResolveBindSum, 8)  // rgba32f running sum, a = sample count
GIB_CONST(uint, kResolveBindOut, 9)  // rgba32f mean
GIB_SHARED_END
#endif
