// probe_relight <-> C++: bindings, group sizes, push constants.
#ifndef GIB_PROBE_RELIGHT_SHARED_H
#define GIB_PROBE_RELIGHT_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvRelightGroup, 64)
GIB_CONST(uint, kPvRelightBindState, 8)        // probe_state (read_write)
GIB_CONST(uint, kPvRelightBindSelection, 9)    // probe_selection
GIB_CONST(uint, kPvRelightBindMaterial, 10)    // probe_gb_material
GIB_CONST(uint, kPvRelightBindNormal, 11)      // probe_gb_normal
GIB_CONST(uint, kPvRelightBindDepth, 12)       // probe_gb_depth
GIB_CONST(uint, kPvRelightBindTexels, 13)      // probe_texel_lists (PvTexelLists header, hits, misses)
GIB_CONST(uint, kPvRelightBindRadiance, 14)    // probe_texel_radiance: vec4 per (selected probe, texel)
GIB_CONST(uint, kPvRelightBindLocal, 15)       // probe_texel_local: float per (selected probe, texel)
GIB_CONST(uint, kPvRelightBindIrradiance, 16)  // probe_irradiance (last frame's values; read)
GIB_CONST(uint, kPvRelightBindProbeRadiance, 17)  // probe_radiance
GIB_CONST(uint, kPvRelightBindVisibility, 18)  // probe_visibility
GIB_CONST(uint, kPvRelightSpecAlpha, 0)
GIB_CONST(uint, kPvRelightSpecLocal, 1)
GIB_CONST(uint, kPvRelightSpecSky, 2)
GIB_CONST(uint, kPvRelightSpecKernel, 3)
// Kernels of probe_relight.comp, in dispatch order.
GIB_CONST(uint, kPvRelightRescale, 0)   // every probe not selected: lighting scale from the sun/sky change
GIB_CONST(uint, kPvRelightClassify, 1)  // one workgroup per selected probe: texels to the hit / miss lists
GIB_CONST(uint, kPvRelightArgs, 2)      // one thread: indirect arguments of the two lists
GIB_CONST(uint, kPvRelightHit, 3)       // one thread per hit texel
GIB_CONST(uint, kPvRelightMiss, 4)      // one thread per miss texel
// A texel list entry: selection entry << 9 | texel (texel < 512).
GIB_CONST(uint, kPvTexelBits, 9)
struct PvRelightPush {
  PvParams pv;
};
GIB_SHARED_END
#endif
