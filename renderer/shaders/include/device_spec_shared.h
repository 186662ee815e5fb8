// Specialization constants the device gives every compute pipeline (renderer/vk/pipelines.cpp),
// measured once when the device is created; a pipeline description that names one itself keeps
// its own value (tests force both forms).
#ifndef GIB_DEVICE_SPEC_SHARED_H
#define GIB_DEVICE_SPEC_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
// 1 where the device's packHalf2x16 rounds to nearest even on every probe value
// (half_rounding_probe.comp: ties, values either side of them, denormal halves, overflow),
// so gib_float_to_half (packing.glsl) may return it directly.
GIB_CONST(uint, kGibSpecNativeHalfRne, 1000)
GIB_CONST(uint, kHalfProbeBindIn, 0)
GIB_CONST(uint, kHalfProbeBindOut, 1)
GIB_CONST(uint, kHalfProbeGroup, 64)
GIB_SHARED_END
#endif
