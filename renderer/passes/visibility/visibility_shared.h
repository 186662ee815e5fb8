#ifndef GIB_VISIBILITY_SHARED_H
#define GIB_VISIBILITY_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#endif
