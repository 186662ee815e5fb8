#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <optional>

#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {

uint32_t rc_active_capacity(const Settings& s) {
  return kProbesPerCascade * std::max(glsl::kRcActivePerProbe, s.params<RadianceCacheSettings>().rays_per_probe);
}

namespace {

bool separate_find(const Settings& s) { return s.params<RadianceCacheSettings>().insertion_find == 1; }

class RadianceCacheUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "radiance_cache_update";
    // probe_trace made them (and, by default, ran insertion round 0, the find); rounds 1 ..
    // cache_max_probe go on from its pending list.
    // Sparse accesses (bench's memory time counts what they move): each pending hit reads at most
    // two slots a round and writes one, and is read and appended once a round; queued cells
    // append an rc_active entry. The separate find (insertion_find 1) reads every hit record and,
    // per record, its key's slots (one plus the probing collisions); without it, probe_hits is
    // not read (every kernel of the shader declares it, so it is bound).
    const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
    const bool find = separate_find(s);
    const double rounds = double(r.cache_max_probe);
    const std::optional<Touched> hits_read =
        find ? std::nullopt : std::optional<Touched>(Touched{0, {}, sizeof(glsl::ProbeHit), false});
    d.slots = {{"probe_hits", Access::read, {}, hits_read},
               {"rc_cells", Access::read_write, {},
                Touched{find ? double(rc_hit_records(s)) : 0.0,
                        {{"hits_pending_round1", 2 * rounds}, {"probing_collisions", find ? 1.0 : 0.0}},
                        sizeof(glsl::RcCell), false}},
               {"rc_active", Access::read_write, {}, Touched{0, {{"cells_queued", 1}}, sizeof(uint32_t), true}},
               {"rc_counters", Access::read_write},
               {"rc_pending", Access::read_write, {},
                Touched{0, {{"hits_pending_round1", 2 * rounds}}, 2 * sizeof(uint32_t), true}}};
    // Read back by bench after its timed frames (never in a frame): what the frame really did
    // (the find's counts, probe_trace's, included).
    d.measured = {{"cells_queued", "rc_counters", offsetof(glsl::RcCounters, active_cells)},
                  {"cells_inserted", "rc_counters", offsetof(glsl::RcCounters, insertions)},
                  {"hits_reused", "rc_counters", offsetof(glsl::RcCounters, reused)},
                  {"hits_dropped", "rc_counters", offsetof(glsl::RcCounters, drops)},
                  {"probing_collisions", "rc_counters", offsetof(glsl::RcCounters, collisions)},
                  {"hits_pending_round1", "rc_counters", sizeof(glsl::RcCounters) + offsetof(glsl::RcRoundArgs, count)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    RcUpdatePush push{make_rc_params(ctx.settings, ctx.frame),
                      {rc_active_capacity(ctx.settings), 0, rc_hit_records(ctx.settings), 0}};
    const std::vector<BufferBinding> buffers{{kRcUpdateBindHits, "probe_hits"},
                                             {kRcUpdateBindCells, "rc_cells"},
                                             {kRcUpdateBindActive, "rc_active"},
                                             {kRcUpdateBindCounters, "rc_counters"},
                                             {kRcUpdateBindPending, "rc_pending"}};
    const SpecConstant group_counts{kRcUpdateSpecGroupCounts, rc_group_counts(ctx.gpu.info(), r) ? 1u : 0u};
    if (separate_find(ctx.settings)) {
      // Round 0 over every hit record in a dispatch of its own (option insertion_find 1, the
      // former layout): keys found in the table are placed and queued, new ones bid and join
      // round 1's list.
      record_compute(ctx, {.shader = "radiance_cache_update.comp",
                           .groups_x = div_up(rc_hit_records(ctx.settings), kRcUpdateGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelFind}, group_counts},
                           .buffers = buffers,
                           .label = "radiance_cache_update/find",
                           .barrier_after = r.cache_max_probe > 0});
    }
    if (r.cache_max_probe == 0) return;  // the find placed or dropped every hit
    if (r.insertion_rounds == 0) {
      // Rounds 1 .. cache_max_probe in one workgroup: one dispatch whatever is pending.
      record_compute(ctx, {.shader = "radiance_cache_update.comp",
                           .groups_x = 1,
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelRounds}, group_counts},
                           .buffers = buffers,
                           .label = "radiance_cache_update/rounds"});
      return;
    }
    // Rounds 1 .. cache_max_probe over the hits still unplaced: indirect, 0 groups once none is.
    for (uint32_t round = 1; round <= r.cache_max_probe; ++round) {
      push.extra.y = round;
      record_compute(ctx, {.shader = "radiance_cache_update.comp",
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelRound}, group_counts},
                           .buffers = buffers,
                           .indirect = "rc_counters",
                           .indirect_offset = sizeof(RcCounters) + uint64_t(round - 1) * sizeof(RcRoundArgs),
                           .label = "radiance_cache_update/round",
                           .barrier_after = round < r.cache_max_probe});
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_radiance_cache_update_pass() { return std::make_unique<RadianceCacheUpdatePass>(); }

RcStats rc_stats_from_bytes(const void* data, size_t bytes) {
  glsl::RcCounters c{};
  std::memcpy(&c, data, std::min(bytes, sizeof(c)));
  RcStats s;
  s.active = c.active_cells;
  s.insertions = c.insertions;
  s.collisions = c.collisions;
  s.drops = c.drops;
  s.reused = c.reused;
  s.dispatch_x = c.dispatch_x;
  return s;
}

RcStats read_rc_stats(Gpu& gpu, const Buffer& counters) {
  glsl::RcCounters c{};
  gpu.download(counters, &c, sizeof(c));
  return rc_stats_from_bytes(&c, sizeof(c));
}

}  // namespace gib
