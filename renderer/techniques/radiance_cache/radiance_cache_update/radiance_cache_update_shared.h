// radiance_cache_update <-> C++: bindings, group size, kernels and push constants.
#ifndef GIB_RADIANCE_CACHE_UPDATE_SHARED_H
#define GIB_RADIANCE_CACHE_UPDATE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kRcUpdateGroup, 64)          // insert/pick: one thread per probe hit record
GIB_CONST(uint, kRcUpdateBindHits, 8)        // readonly ProbeHit probe_hits[]
GIB_CONST(uint, kRcUpdateBindCells, 9)       // coherent RcCell rc_cells[2^cache_log2_cells]
GIB_CONST(uint, kRcUpdateBindActive, 10)     // uint rc_active[capacity]: queued cell indices
GIB_CONST(uint, kRcUpdateBindCounters, 11)   // RcCounters (indirect args first)
GIB_CONST(uint, kRcUpdateSpecKernel, 0)      // 0: insert, 1: indirect args, 2: pick
GIB_CONST(uint, kRcUpdateKernelInsert, 0)
GIB_CONST(uint, kRcUpdateKernelArgs, 1)
GIB_CONST(uint, kRcUpdateKernelPick, 2)  // lowest hit id of each queued cell (determinism)
// Active-list capacity per probe: one entry per ray at most (64, or rays_per_probe if larger),
// so the list cannot overflow (a cell is queued at most once per frame, by one of its hits).
GIB_CONST(uint, kRcActivePerProbe, 64)
struct RcUpdatePush {
  RcParams rc;
  uvec4 extra;  // x: active-list capacity (entries), y: insertion round (0 .. cache_max_probe)
};
GIB_SHARED_END
#endif
