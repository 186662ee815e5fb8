// probe_select <-> C++: bindings, group size, push constants.
#ifndef GIB_PROBE_SELECT_SHARED_H
#define GIB_PROBE_SELECT_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvSelectGroup, 256)       // one workgroup: ordered (deterministic) compaction
GIB_CONST(uint, kPvSelectBindState, 8)     // probe_state (read_write)
GIB_CONST(uint, kPvSelectBindSelection, 9) // probe_selection (write)
struct PvSelectPush {
  PvParams pv;
};
GIB_SHARED_END
#endif
