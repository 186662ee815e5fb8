// Deterministic insertion into the world radiance cache, shared by probe_trace (round 0, the
// find, fused into the trace: each ray hit triggers its cache update, as the seed's) and
// radiance_cache_update (rounds 1 .. cache_max_probe). The includer declares, before including:
//   RcParams rc; uvec4 extra (push constants: x active-list capacity, z pending-list capacity)
//   coherent buffer { RcCounters counters; RcRoundArgs rounds[]; }
//   coherent buffer { uvec2 rc_pending[]; }, writeonly buffer { uint rc_active[]; }
//   RC_CELL_BUFFER(..., coherent), and #define RC_INSERT_SPEC_GROUP_COUNTS (a constant_id);
// and enables GL_KHR_shader_subgroup_basic, _ballot and _arithmetic.
// and calls, in uniform control flow: rc_insert_begin(), rc_insert_find(id, key) (round 0) or
// rc_insert_step(round, id, key) (round >= 1) per hit, rc_insert_flush() at the end.
#ifndef GIB_RC_INSERT_GLSL
#define GIB_RC_INSERT_GLSL
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"

const uint kNoCell = 0xffffffffu;

// ---- aggregated counters and list appends. Counters are summed per subgroup; on GPUs
// (kGroupCounts) the subgroups' sums go to group-shared totals that reach the buffer once per
// workgroup (flush_counts), since atomics on one address serialise and every subgroup of the
// find dispatch has reused hits to count; on CPU devices a group barrier costs more than the
// atomics, so each subgroup adds to the buffer. Used in uniform control flow (every thread of
// the group).
layout(constant_id = RC_INSERT_SPEC_GROUP_COUNTS) const bool kGroupCounts = true;
shared uint s_counts[4];  // collisions, drops, insertions, reused
#define RC_COUNT(INDEX, COUNTER, N)                                                                    \
  {                                                                                                    \
    uint total_ = subgroupAdd(N);                                                                      \
    if (subgroupElect() && total_ != 0u) {                                                             \
      if (kGroupCounts)                                                                                \
        atomicAdd(s_counts[INDEX], total_);                                                            \
      else                                                                                             \
        atomicAdd(COUNTER, total_);                                                                    \
    }                                                                                                  \
  }

// Appends for every thread whose WANT is true: SLOT receives its entry (consecutive within the
// subgroup), LENGTH counts the entries, and GROUPS the groups of GROUP threads the list spans up
// to CAP entries: each subgroup adds the multiples of GROUP it crosses, so the sum over all of
// them is ceil(min(length, CAP) / GROUP) whatever the order.
#define RC_APPEND(WANT, SLOT, LENGTH, GROUPS, GROUP, CAP)                                  \
  {                                                                                        \
    uvec4 ballot_ = subgroupBallot(WANT);                                                  \
    uint n_ = subgroupBallotBitCount(ballot_), base_ = 0u;                                 \
    if (n_ != 0u) {                                                                        \
      if (subgroupElect()) {                                                               \
        base_ = atomicAdd(LENGTH, n_);                                                     \
        uint lo_ = min(base_, CAP), hi_ = min(base_ + n_, CAP);                            \
        uint crossed_ = (hi_ + (GROUP) - 1u) / (GROUP) - (lo_ + (GROUP) - 1u) / (GROUP);   \
        if (crossed_ != 0u) atomicAdd(GROUPS, crossed_);                                   \
      }                                                                                    \
      base_ = subgroupBroadcastFirst(base_);                                               \
    }                                                                                      \
    SLOT = base_ + subgroupBallotExclusiveBitCount(ballot_);                               \
  }

// ---- deterministic insertion (radiance_cache.glsl, "Insertion"). Round r = 0 .. max_probe lets
// every key not yet in the table bid for slot first + r of its probe sequence: a bid is the key
// tagged with the round's parity (2 | r & 1), the largest bid wins (atomicMax), so the winner
// depends on the set of keys, not on thread order; the winner commits (tag -> 1) in round r + 1,
// the losers move on; keys still unplaced after round max_probe - 1's commit are dropped.
//
// Round 0 (the find, in probe_trace, every hit record): the key is searched in the table as the
// frame found it (nothing but round-0 bids is written during the trace, and only into slots
// empty at the frame's start; cells are never removed, so every slot before a committed key is
// occupied). Found at step s: placed (the rounds would find it in round s, counting s
// collisions). All max_probe slots held by other keys: dropped (every round counts a collision).
// Else the key is new: it bids here if its first slot is empty (or holds round-0 bids), and joins
// the pending list of round 1. Round r >= 1 (radiance_cache_update, over that list): looks at
// slot first + r - 1 (its own bid of round r - 1 won: commit; a sibling hit committed it: found;
// else a collision), then bids for slot first + r, or, in round max_probe, is dropped; still
// unplaced hits join round r + 1's list, so a round with nothing left has nothing to do. Each hit
// meets exactly the table states and takes exactly the steps of the former design (every hit in
// every round), so the table and the counters are the same.

// Bids `bid` for slot i, which held v when read: empty, or holding this round's bids (same
// parity tag). Anything else (a committed key, the previous round's winner) is occupied.
void bid_for(uint i, uint v, uint bid) {
  if (v == 0u || (v & 3u) == (bid & 3u)) atomicMax(rc_cells[i].key, bid);
}

// A placed hit: queue its cell for shading unless it was shaded recently (reused), and offer the
// hit as the cell's shading input: RcCell.hit_index holds ~(lowest hit id) of the queued cell's
// hits (atomicMax of ~id; radiance_cache_shade reads it and resets it to 0, so it is 0 whenever
// this pass starts). Which hit shades the cell then depends on the set of hits, not on who won
// the queueing race. Returns true when this hit appended the cell to rc_active.
bool queue_cell(uint cell, uint id, inout uint reused) {
  uint now = rc.misc.x + 1u;
  // A plain (coherent) read, not an atomic one: every hit of a busy cell reads it, and atomics on
  // one address serialise. A stale read changes nothing: shaded_frame moves only from a value
  // that is due (not reused) to `now`, by the swap below, so a hit that misses that write still
  // finds the cell due, loses the swap and goes on as one that saw `now`.
  uint shaded = rc_cells[cell].shaded_frame;
  bool mine = false;
  if (shaded != now) {
    if (shaded != 0u && now - shaded < rc.misc.y) {
      reused = 1u;
      return false;
    }
    // Within this pass shaded_frame only ever changes to `now`: losing the swap means another
    // hit queued the cell.
    mine = atomicCompSwap(rc_cells[cell].shaded_frame, shaded, now) == shaded;
  }
  atomicMax(rc_cells[cell].hit_index, ~id);
  return mine;
}

struct Outcome {
  uint collisions, drops, insertions, reused;
  uint cell;     // placed: the cell to queue, else kNoCell
  bool pending;  // goes on to the next round
};

Outcome find_hit(uint key) {
  Outcome o = Outcome(0u, 0u, 0u, 0u, kNoCell, false);
  if (key == 0u) return o;
  uint mask = rc_cell_mask(), first = rc_cell_first_slot(key), n = rc_max_probe();
  uint s = 0u, v = 0u;
  for (; s < n; ++s) {
    v = rc_cells[(first + s) & mask].key;
    if (v == key) {
      o.collisions = s;
      o.cell = (first + s) & mask;
      return o;
    }
    if ((v & 3u) != 1u) break;  // empty when the frame started (a round-0 bid at most)
  }
  if (s == n) {
    o.collisions = n;
    o.drops = 1u;
    return o;
  }
  if (s == 0u) bid_for(first & mask, v, (key & ~3u) | 2u);
  o.pending = true;
  return o;
}

Outcome round_hit(uint key, uint round) {
  Outcome o = Outcome(0u, 0u, 0u, 0u, kNoCell, false);
  uint mask = rc_cell_mask(), first = rc_cell_first_slot(key), hash = key & ~3u;
  uint last_bid = hash | (2u + ((round + 1u) & 1u));
  uint i = (first + round - 1u) & mask;
  uint v = rc_cells[i].key;
  if (v == key) {
    o.cell = i;
    return o;
  }
  if (v == last_bid) {
    // Our bid of the previous round won: commit it (one of the key's hits counts it).
    if (atomicCompSwap(rc_cells[i].key, v, key) == v) o.insertions = 1u;
    o.cell = i;
    return o;
  }
  o.collisions = 1u;  // passed last round's slot
  if (round == rc_max_probe()) {
    o.drops = 1u;
    return o;
  }
  i = (first + round) & mask;
  v = rc_cells[i].key;
  if (v == key) {  // not reachable (a key enters an empty slot only by its own bid); kept as a guard
    o.cell = i;
    return o;
  }
  bid_for(i, v, hash | (2u + (round & 1u)));
  o.pending = true;
  return o;
}

// One hit's step in `round`: the hit record `id` with its committed key (round 0: every hit
// record, key 0 for a miss or a ray inside geometry) or a pending-list entry (round >= 1; key 0
// past the list's length): nothing to do for key 0, but every thread joins the subgroup's
// counters and appends, which need uniform control flow.
void rc_insert_step(uint round, uint id, uint key) {
  Outcome o = Outcome(0u, 0u, 0u, 0u, kNoCell, false);
  if (key != 0u) o = round == 0u ? find_hit(key) : round_hit(key, round);
  bool queued = o.cell != kNoCell && queue_cell(o.cell, id, o.reused);

  // Uniform control flow from here: aggregated counters and appends.
  RC_COUNT(0, counters.collisions, o.collisions);
  RC_COUNT(1, counters.drops, o.drops);
  RC_COUNT(2, counters.insertions, o.insertions);
  RC_COUNT(3, counters.reused, o.reused);
  uint slot;
  RC_APPEND(queued, slot, counters.active_cells, counters.dispatch_x, kRcShadeGroup, extra.x);
  if (queued && slot < extra.x) rc_active[slot] = o.cell;  // capacity >= hit records: always
  if (round < rc_max_probe()) {
    uint next = round + 1u;
    RC_APPEND(o.pending, slot, rounds[next - 1u].count, rounds[next - 1u].groups_x, kRcUpdateGroup, extra.z);
    if (o.pending) rc_pending[(next & 1u) * extra.z + slot] = uvec2(id, key);
  }
}

// Whether thread `id` of a round-0 dispatch has a hit record (one per ray of the updated cascade).
bool rc_is_hit_record(uint id) { return id < kProbeGridDim * kProbeGridDim * kProbeGridDim * rc_rays_per_probe(); }

// Round 0, the find, for thread `id` and its hit record's committed key (0 past the records).
// Thread 0 also writes the y, z of every indirect dispatch of the insertion (the counters arrive
// zeroed: last frame's probe_trace zeroed this frame's copy).
void rc_insert_find(uint id, uint key) {
  if (id == 0u) {
    counters.dispatch_y = 1u;
    counters.dispatch_z = 1u;
    for (uint r = 0u; r < rc_max_probe(); ++r) {
      rounds[r].groups_y = 1u;
      rounds[r].groups_z = 1u;
    }
  }
  rc_insert_step(0u, id, key);
}

// Zeroes the group's counter totals (kGroupCounts); call first, in uniform control flow.
void rc_insert_begin() {
  if (kGroupCounts) {
    if (gl_LocalInvocationIndex < 4u) s_counts[gl_LocalInvocationIndex] = 0u;
    barrier();
  }
}


// The group's counter totals into the buffer: one atomic per counter and workgroup.
void rc_insert_flush() {
  if (!kGroupCounts) return;
  barrier();
  uint t = gl_LocalInvocationIndex;
  if (t < 4u && s_counts[t] != 0u) {
    if (t == 0u) atomicAdd(counters.collisions, s_counts[t]);
    if (t == 1u) atomicAdd(counters.drops, s_counts[t]);
    if (t == 2u) atomicAdd(counters.insertions, s_counts[t]);
    if (t == 3u) atomicAdd(counters.reused, s_counts[t]);
  }
}

#endif  // GIB_RC_INSERT_GLSL
