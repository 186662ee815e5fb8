// pixel_upscale <-> C++: bindings, group size, push constants.
#ifndef GIB_PIXEL_UPSCALE_SHARED_H
#define GIB_PIXEL_UPSCALE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvUpscaleGroup, 8)
GIB_CONST(uint, kPvUpscaleBindPosition, 8)
GIB_CONST(uint, kPvUpscaleBindNormal, 9)
GIB_CONST(uint, kPvUpscaleBindEmissive, 10)
GIB_CONST(uint, kPvUpscaleBindGiY, 11)
GIB_CONST(uint, kPvUpscaleBindGiC, 12)
GIB_CONST(uint, kPvUpscaleBindIrradiance, 13)  // gi_irradiance (rgba32f, irradiance / pi)
GIB_CONST(uint, kPvUpscaleBindDirect, 14)      // gi_direct_irradiance: 0 (direct_lighting has it all)
struct PvUpscalePush {
  PvParams pv;
};
GIB_SHARED_END
#endif
