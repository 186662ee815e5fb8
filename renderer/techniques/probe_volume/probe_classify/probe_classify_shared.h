// probe_classify <-> C++: bindings, group size, push constants.
#ifndef GIB_PROBE_CLASSIFY_SHARED_H
#define GIB_PROBE_CLASSIFY_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kPvClassifyGroup, 64)         // one thread per selected probe
GIB_CONST(uint, kPvClassifyBindState, 8)      // probe_state (read_write)
GIB_CONST(uint, kPvClassifyBindSelection, 9)  // probe_selection
struct PvClassifyPush {
  PvParams pv;
};
GIB_SHARED_END
#endif
