// radiance_cache_update: inserts this frame's probe hits into the world radiance cache and
// queues the cells that need shading (the idTech 8 "Global Illumination" talk,
// "Sampling the World": each ray hit triggers a cache update; spatial hashing [Gautron 2020],
// 25 cm cells with distance LODs, linear probing, an active-cell counter and list, indirect
// dispatch args). Insertion round 0, the find, runs in probe_trace as each ray is traced (the
// seed's: the trace triggers the cache update); this pass goes on from its pending list.
// Kernels (labels radiance_cache_update/<kernel>; the insertion's code: include/rc_insert.glsl):
//   find   (option insertion_find 1 only: the former layout) one thread per hit record; misses
//          are skipped. The hit's committed key (made by probe_trace: rc_cell_key,
//          radiance_cache.glsl: LOD = 2^floor(log2(1 + d_cam / lod_distance)), cell = floor(p /
//          (cell_size * LOD)), key = hash(cell, LOD) | 1) is searched over at most
//          cache_max_probe slots: a key in the table is placed now, a new key bids for its first
//          slot if empty (insertion round 0) and joins the pending list (hit id, key) of round
//          1, a key whose slots are all taken is dropped. By default probe_trace does this.
//   rounds r = 1 .. cache_max_probe in one workgroup (option insertion_rounds 0), or `round`,
//          one indirect dispatch per round over the hits still pending (0 groups once none is;
//          insertion_rounds 1): commit a won bid, else bid for the next slot (deterministic
//          insertion, rc_insert.glsl); still pending hits join round r + 1's list.
// A placed hit queues its cell unless its shaded_frame is within cache_reuse_frames: the queued
// marker is RcCell.shaded_frame itself, atomicCompSwap'd from its old value to frame + 1 (so a
// cell is queued once per frame; radiance_cache_shade then writes the radiance, and shaded_frame
// already holds frame + 1); the winner appends the cell to rc_active and counts the shade's
// indirect args as it goes. Every hit of a queued cell offers ~id to RcCell.hit_index
// (atomicMax): the shade uses the lowest hit id, whoever won the race, and resets it to 0.
// Counters (RcCounters, radiance_cache_shared.h; aggregated per subgroup), per hit record that
// is a hit: `drops` (no slot within cache_max_probe), `insertions` (claimed an empty slot),
// `reused` (found a cell shaded in an earlier frame within cache_reuse_frames), or none of them
// (found a cell queued this frame by another hit, or queued it itself); `collisions` = probing
// steps past occupied slots of other keys; `active` = cells queued. So insertions + reused +
// drops <= hits and insertions <= active. The same table and counters as the former design
// (every round a dispatch over every hit record, then a pick and an args kernel).
// Work: none declared (probe_trace declares the rays); bench reads back cells_queued,
// cells_inserted, hits_reused, hits_dropped and hits_pending_round1 (the hits of new keys) after
// its timed frames.
// Slots: reads probe_hits (the find kernel's); reads and writes rc_cells, rc_active,
// rc_counters and rc_pending, which probe_trace creates (rc_counters: ping-pong, zeroed a frame
// ahead; probe_trace.h).
// Limits: cells are never evicted (a long camera path fills the table, then insertions are
// dropped and counted); between this pass and radiance_cache_shade a queued cell reads as shaded
// this frame (readers run after the shade); the key ignores the normal, so both faces of a wall
// thinner than a cell share one radiance.
#pragma once
#include <cstdint>
#include <memory>

#include "renderer/graph/pass.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"

namespace gib {
std::unique_ptr<Pass> make_radiance_cache_update_pass();

// The counters as read back from the `rc_counters` buffer (its first 32 bytes: RcCounters).
struct RcStats {
  uint32_t active = 0, insertions = 0, collisions = 0, drops = 0, reused = 0;
  uint32_t dispatch_x = 0;
};
RcStats read_rc_stats(Gpu& gpu, const Buffer& counters);
RcStats rc_stats_from_bytes(const void* data, size_t bytes);  // e.g. Executor::read_buffer's
}  // namespace gib
