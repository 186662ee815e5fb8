#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

uint32_t active_capacity(const Settings& s) {
  return kProbesPerCascade * std::max(glsl::kRcActivePerProbe, s.params<RadianceCacheSettings>().rays_per_probe);
}

class RadianceCacheUpdatePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "radiance_cache_update";
    ResourceDesc cells{Format::buffer, SizeRule::buffer};
    cells.bytes = (uint64_t(1) << s.params<RadianceCacheSettings>().cache_log2_cells) * sizeof(glsl::RcCell);
    cells.persistent = true;
    cells.values = non_negative_values().encoded(Encoding::rgb9e5).layout(  // cell radiance
        sizeof(glsl::RcCell) / 4, offsetof(glsl::RcCell, radiance) / 4, 1);
    ResourceDesc active{Format::buffer, SizeRule::buffer};
    active.bytes = uint64_t(active_capacity(s)) * sizeof(uint32_t);
    ResourceDesc counters{Format::buffer, SizeRule::buffer};
    counters.bytes = sizeof(glsl::RcCounters);
    d.slots = {{"probe_hits", Access::read},
               {"rc_cells", Access::read_write, cells},
               {"rc_active", Access::write, active},
               {"rc_counters", Access::write, counters}};
    d.work = rc_cache_work(s);
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    RcUpdatePush push{make_rc_params(ctx.settings, ctx.frame), {active_capacity(ctx.settings), 0, 0, 0}};
    // Last frame's shade read rc_counters (indirect args): order the fill after it. (rc_cells is
    // persistent: the executor zeroes it when it creates it.)
    ctx.cmd.barrier(kStageCompute, kStageTransfer);
    ctx.cmd.begin_label("radiance_cache_update/reset");
    ctx.cmd.fill(ctx.buffer("rc_counters"), 0);
    ctx.cmd.end_label();
    ctx.cmd.barrier(kStageTransfer, kStageCompute);

    const std::vector<BufferBinding> buffers{{kRcUpdateBindHits, "probe_hits"},
                                             {kRcUpdateBindCells, "rc_cells"},
                                             {kRcUpdateBindActive, "rc_active"},
                                             {kRcUpdateBindCounters, "rc_counters"}};
    // Insertion in cache_max_probe + 1 rounds (radiance_cache_update.comp): round r bids for the
    // r-th slot of each unplaced key's probe sequence; the last round settles and queues.
    ctx.cmd.begin_label("radiance_cache_update/insert");
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    uint32_t hits = kProbesPerCascade * r.rays_per_probe;
    for (uint32_t round = 0; round <= r.cache_max_probe; ++round) {
      push.extra.y = round;
      record_compute(ctx, {.shader = "radiance_cache_update.comp",
                           .groups_x = div_up(hits, kRcUpdateGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelInsert}},
                           .buffers = buffers});
      ctx.cmd.barrier(kStageCompute, kStageCompute);
    }
    ctx.cmd.end_label();

    ctx.cmd.begin_label("radiance_cache_update/pick");
    record_compute(ctx, {.shader = "radiance_cache_update.comp",
                         .groups_x = div_up(hits, kRcUpdateGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelPick}},
                         .buffers = buffers});
    ctx.cmd.end_label();
    ctx.cmd.barrier(kStageCompute, kStageCompute);

    ctx.cmd.begin_label("radiance_cache_update/args");
    record_compute(ctx, {.shader = "radiance_cache_update.comp",
                         .groups_x = 1,
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kRcUpdateSpecKernel, kRcUpdateKernelArgs}},
                         .buffers = buffers});
    ctx.cmd.end_label();
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
