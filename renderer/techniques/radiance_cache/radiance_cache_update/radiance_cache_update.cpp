#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>

#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

uint32_t active_capacity(const Settings& s) {
  return kProbesPerCascade * std::max(glsl::kRcActivePerProbe, s.params<RadianceCacheSettings>().rays_per_probe);
}

uint32_t hit_records(const Settings& s) { return kProbesPerCascade * s.params<RadianceCacheSettings>().rays_per_probe; }

class RadianceCacheUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
    PassDecl d;
    d.name = "radiance_cache_update";
    ResourceDesc cells{Format::buffer, SizeRule::buffer};
    cells.bytes = (uint64_t(1) << r.cache_log2_cells) * sizeof(glsl::RcCell);
    cells.persistent = true;
    cells.values = non_negative_values().encoded(Encoding::rgb9e5).layout(  // cell radiance
        sizeof(glsl::RcCell) / 4, offsetof(glsl::RcCell, radiance) / 4, 1);
    ResourceDesc active{Format::buffer, SizeRule::buffer};
    active.bytes = uint64_t(active_capacity(s)) * sizeof(uint32_t);
    // RcCounters, then the indirect args and length of insertion rounds 1 .. cache_max_probe.
    ResourceDesc counters{Format::buffer, SizeRule::buffer};
    counters.bytes = sizeof(glsl::RcCounters) + uint64_t(r.cache_max_probe) * sizeof(glsl::RcRoundArgs);
    // The hits still unplaced after a round, (hit id, key): two lists, rounds alternate.
    ResourceDesc pending{Format::buffer, SizeRule::buffer};
    pending.bytes = 2 * uint64_t(hit_records(s)) * 2 * sizeof(uint32_t);
    d.slots = {{"probe_hits", Access::read},
               {"rc_cells", Access::read_write, cells},
               {"rc_active", Access::write, active},
               {"rc_counters", Access::write, counters},
               {"rc_pending", Access::write, pending}};
    d.work = {{"hits", double(hit_records(s))}};
    // Read back by bench after its timed frames (never in a frame): what the frame really did.
    d.measured = {{"cells_queued", "rc_counters", offsetof(glsl::RcCounters, active_cells)},
                  {"cells_inserted", "rc_counters", offsetof(glsl::RcCounters, insertions)},
                  {"hits_reused", "rc_counters", offsetof(glsl::RcCounters, reused)},
                  {"hits_dropped", "rc_counters", offsetof(glsl::RcCounters, drops)},
                  {"hits_pending_round1", "rc_counters", sizeof(glsl::RcCounters) + offsetof(glsl::RcRoundArgs, count)}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeviceInfo& info = ctx.gpu.info();
    if (!info.subgroup_ballot || !info.subgroup_arithmetic)
      throw std::runtime_error(
          "radiance_cache_update: the device lacks compute subgroup ballot/arithmetic operations "
          "(VkPhysicalDeviceSubgroupProperties), which radiance_cache_update.comp needs");
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    const uint32_t hits = hit_records(ctx.settings);
    RcUpdatePush push{make_rc_params(ctx.settings, ctx.frame), {active_capacity(ctx.settings), 0, hits, 0}};
    // Last frame's shade read rc_counters (indirect args): order the fill after it. (rc_cells is
    // persistent: the executor zeroes it when it creates it.)
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.begin_label("radiance_cache_update/reset");
    ctx.cmd.fill(ctx.buffer("rc_counters"), 0);
    ctx.cmd.end_label();
    ctx.cmd.barrier(kStageTransfer, kStageCompute);

    // Counters summed per workgroup on GPUs; on a CPU device a group barrier costs more.
    const bool per_group = r.update_counters == 0 ? !info.is_software() : r.update_counters == 1;
    const SpecConstant group_counts{kRcUpdateSpecGroupCounts, per_group ? 1u : 0u};
    const std::vector<BufferBinding> buffers{{kRcUpdateBindHits, "probe_hits"},
                                             {kRcUpdateBindCells, "rc_cells"},
                                             {kRcUpdateBindActive, "rc_active"},
                                             {kRcUpdateBindCounters, "rc_counters"},
                                             {kRcUpdateBindPending, "rc_pending"}};
    // Round 0 over every hit record: keys found in the table are placed and queued at once, new
    // ones bid and join round 1's list (radiance_cache_update.comp).
    record_compute(ctx, {.shader = "radiance_cache_update.comp",
                         .groups_x = div_up(hits, kRcUpdateGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelFind}, group_counts},
                         .buffers = buffers,
                         .label = "radiance_cache_update/find",
                         .barrier_after = r.cache_max_probe > 0});
    if (r.cache_max_probe == 0) return;
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
