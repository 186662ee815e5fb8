// radiance_cache_update <-> C++: bindings, group size, kernels and push constants.
#ifndef GIB_RADIANCE_CACHE_UPDATE_SHARED_H
#define GIB_RADIANCE_CACHE_UPDATE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kRcUpdateGroup, 256)         // find: one thread per probe hit record; rounds: per pending hit
GIB_CONST(uint, kRcUpdateBindHits, 8)        // readonly ProbeHit probe_hits[] (the find kernel's, option insertion_find 1)
GIB_CONST(uint, kRcUpdateBindCells, 9)       // coherent RcCell rc_cells[2^cache_log2_cells]
GIB_CONST(uint, kRcUpdateBindActive, 10)     // uint rc_active[capacity]: queued cell indices
GIB_CONST(uint, kRcUpdateBindCounters, 11)   // RcCounters (indirect args first), then RcRoundArgs[max_probe]
GIB_CONST(uint, kRcUpdateBindPending, 12)    // uvec2 rc_pending[2 * hits]: (hit id, key), two lists
GIB_CONST(uint, kRcUpdateSpecKernel, 0)      // 0: find (round 0; option insertion_find 1, else probe_trace runs it), 1: round r >= 1, 2: rounds 1 .. max_probe in one group
GIB_CONST(uint, kRcUpdateSpecGroupCounts, 1) // bool: counters summed per workgroup in shared memory (GPUs; not on CPU devices)
GIB_CONST(uint, kRcUpdateKernelFind, 0)
GIB_CONST(uint, kRcUpdateKernelRound, 1)
GIB_CONST(uint, kRcUpdateKernelRounds, 2)
// Active-list capacity per probe: one entry per ray at most (64, or rays_per_probe if larger),
// so the list cannot overflow (a cell is queued at most once per frame, by one of its hits).
GIB_CONST(uint, kRcActivePerProbe, 64)
// Insertion round r (1 .. max_probe) runs over the hits still unplaced after round r - 1: its
// indirect args and list length, in rc_counters after RcCounters (byte offset 32 + 16 (r - 1)).
struct RcRoundArgs {
  uint groups_x, groups_y, groups_z;  // VkDispatchIndirectCommand: ceil(count / kRcUpdateGroup), 1, 1
  uint count;                         // pending hits in the round's list
};
struct RcUpdatePush {
  RcParams rc;
  uvec4 extra;  // x: active-list capacity (entries), y: insertion round (0 .. cache_max_probe),
                // z: pending-list capacity (hit records)
};
GIB_SHARED_END
#endif
