#ifndef GIB_SHADOWS_PCF_SHARED_H
#define GIB_SHADOWS_PCF_SHARED_H
#include "shadow_cascades_shared.h"
#endif
