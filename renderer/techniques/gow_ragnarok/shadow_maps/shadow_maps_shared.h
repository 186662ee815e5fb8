#ifndef GIB_SHADOW_MAPS_SHARED_H
#define GIB_SHADOW_MAPS_SHARED_H
#include "renderer/techniques/gow_ragnarok/include/gow_shadow_shared.h"
#endif
