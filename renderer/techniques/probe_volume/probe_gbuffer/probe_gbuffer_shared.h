// probe_gbuffer <-> C++: bindings, group size, push constants.
#ifndef GIB_PROBE_GBUFFER_SHARED_H
#define GIB_PROBE_GBUFFER_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvGbufferGroup, 64)          // one workgroup per traced probe
GIB_CONST(uint, kPvGbufferBindState, 8)       // probe_state (read_write)
GIB_CONST(uint, kPvGbufferBindSelection, 9)   // probe_selection (read)
GIB_CONST(uint, kPvGbufferBindMaterial, 10)   // probe_gb_material (read_write)
GIB_CONST(uint, kPvGbufferBindNormal, 11)     // probe_gb_normal (read_write)
GIB_CONST(uint, kPvGbufferBindDepth, 12)      // probe_gb_depth (read_write)
GIB_CONST(uint, kPvGbufferSpecAlpha, 0)
GIB_CONST(uint, kPvGbufferSpecSun, 1)
// Back faces count towards "inside geometry" only when hit within this many spacings.
GIB_CONST(float, kPvBackfaceReach, 1.0)
struct PvGbufferPush {
  PvParams pv;
};
GIB_SHARED_END
#endif
