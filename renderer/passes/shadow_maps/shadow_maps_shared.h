#ifndef GIB_SHADOW_MAPS_SHARED_H
#define GIB_SHADOW_MAPS_SHARED_H
#include "shadow_cascades_shared.h"
#endif
