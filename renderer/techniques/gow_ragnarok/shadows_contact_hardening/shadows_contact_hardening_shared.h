#ifndef GIB_SHADOWS_CONTACT_HARDENING_SHARED_H
#define GIB_SHADOWS_CONTACT_HARDENING_SHARED_H
#include "shadow_cascades_shared.h"
#endif
