#ifndef GIB_SHADOWS_CONTACT_HARDENING_SHARED_H
#define GIB_SHADOWS_CONTACT_HARDENING_SHARED_H
#include "renderer/techniques/gow_ragnarok/include/gow_shadow_shared.h"
#endif
