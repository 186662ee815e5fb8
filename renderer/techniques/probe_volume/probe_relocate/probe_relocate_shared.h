// probe_relocate <-> C++: bindings, group size, push constants.
#ifndef GIB_PROBE_RELOCATE_SHARED_H
#define GIB_PROBE_RELOCATE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvRelocateGroup, 64)        // one workgroup per traced probe
GIB_CONST(uint, kPvRelocateBindState, 8)     // probe_state (read_write)
GIB_CONST(uint, kPvRelocateBindSelection, 9) // probe_selection
GIB_CONST(uint, kPvRelocateBindDepth, 10)    // probe_gb_depth
// A probe is inside geometry when more than this share of its hits are back faces.
GIB_CONST(float, kPvInsideBackfaces, 0.25)
// ... and too near geometry when its nearest hit is closer than this many spacings.
GIB_CONST(float, kPvNearSpacings, 0.2)
// The offset stays within this many spacings of the cell centre, per axis.
GIB_CONST(float, kPvMaxOffsetSpacings, 0.45)
struct PvRelocatePush {
  PvParams pv;
};
GIB_SHARED_END
#endif
