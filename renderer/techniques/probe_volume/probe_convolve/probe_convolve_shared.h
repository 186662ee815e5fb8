// probe_convolve <-> C++: bindings, group size, push constants.
#ifndef GIB_PROBE_CONVOLVE_SHARED_H
#define GIB_PROBE_CONVOLVE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
// One workgroup per selected probe: 100 radiance + 25 irradiance texels, rounded up (the seed's 128).
GIB_CONST(uint, kPvConvolveGroup, 128)
GIB_CONST(uint, kPvConvolveBindState, 8)        // probe_state (read_write)
GIB_CONST(uint, kPvConvolveBindSelection, 9)    // probe_selection
GIB_CONST(uint, kPvConvolveBindMaterial, 10)    // probe_gb_material (emission of hit texels)
GIB_CONST(uint, kPvConvolveBindDepth, 11)       // probe_gb_depth
GIB_CONST(uint, kPvConvolveBindRadianceIn, 12)  // probe_texel_radiance
GIB_CONST(uint, kPvConvolveBindLocal, 13)       // probe_texel_local
GIB_CONST(uint, kPvConvolveBindIrradiance, 14)  // probe_irradiance (read_write)
GIB_CONST(uint, kPvConvolveBindRadiance, 15)    // probe_radiance (read_write)
GIB_CONST(uint, kPvConvolveBindVisibility, 16)  // probe_visibility (read_write)
GIB_CONST(uint, kPvConvolveSpecSky, 0)
struct PvConvolvePush {
  PvParams pv;
};
GIB_SHARED_END
#endif
