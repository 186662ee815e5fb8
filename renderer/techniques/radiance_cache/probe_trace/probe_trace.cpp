#include "renderer/techniques/radiance_cache/probe_trace/probe_trace.h"

#include <fmt/format.h>

#include <cstddef>
#include <stdexcept>

#include "renderer/techniques/radiance_cache/probe_trace/probe_trace_shared.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"

namespace gib {
namespace {

class ProbeTracePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    const RadianceCacheSettings& r = s.params<RadianceCacheSettings>();
    const uint32_t rays = r.rays_per_probe;
    if (rays == 0 || rays > glsl::kProbeTraceMaxRays)
      throw GraphError(fmt::format("probe_trace: rays_per_probe must be 1..{}, got {}", glsl::kProbeTraceMaxRays, rays));
    if (r.cascades == 0 || r.cascades > glsl::kMaxCascades)
      throw GraphError(fmt::format("probe_trace: cascades must be 1..{}, got {}", glsl::kMaxCascades, r.cascades));
    PassDecl d;
    d.name = "probe_trace";
    d.traces_rays = true;  // BVH walk in the shader (PassDecl::traces_rays)
    ResourceDesc hits{Format::buffer, SizeRule::buffer};
    hits.bytes = uint64_t(kProbesPerCascade) * rays * sizeof(glsl::ProbeHit);
    hits.values = non_negative_values().layout(sizeof(glsl::ProbeHit) / 4, offsetof(glsl::ProbeHit, distance) / 4, 1);
    // The world radiance cache, which the trace's insertion round 0 searches and bids into.
    ResourceDesc cells{Format::buffer, SizeRule::buffer};
    cells.bytes = (uint64_t(1) << r.cache_log2_cells) * sizeof(glsl::RcCell);
    cells.persistent = true;  // the executor zeroes it when it creates it
    cells.values = non_negative_values().encoded(Encoding::rgb9e5).layout(  // cell radiance
        sizeof(glsl::RcCell) / 4, offsetof(glsl::RcCell, radiance) / 4, 1);
    ResourceDesc active{Format::buffer, SizeRule::buffer};
    active.bytes = uint64_t(rc_active_capacity(s)) * sizeof(uint32_t);
    // RcCounters, then the indirect args and length of insertion rounds 1 .. cache_max_probe.
    // Two copies (ping-pong by frame): this frame's counts into one while its kernel zeroes the
    // other, last frame's, for the next frame (read_prev below), so no fill and no barrier
    // precede the trace. Frames are fenced, so last frame's readers (the shade's indirect args)
    // are done with that copy. Persistent: both copies start zeroed.
    ResourceDesc counters{Format::buffer, SizeRule::buffer};
    counters.bytes = sizeof(glsl::RcCounters) + uint64_t(r.cache_max_probe) * sizeof(glsl::RcRoundArgs);
    counters.persistent = true;
    // The hits still unplaced after a round, (hit id, key): two lists, rounds alternate.
    ResourceDesc pending{Format::buffer, SizeRule::buffer};
    pending.bytes = 2 * uint64_t(rc_hit_records(s)) * 2 * sizeof(uint32_t);
    // The find touches the table sparsely (bench's memory time counts what it moves, not the
    // 2^cache_log2_cells x 16 bytes): each hit record reads its key's slots, one plus its probing
    // collisions, and writes at most one cell (a bid, the queue marker, hit_index); each queued
    // cell appends one rc_active entry, each new key one rc_pending entry. Nothing of them with
    // option insertion_find 1 (radiance_cache_update's find then does it).
    const bool find = r.insertion_find == 0;
    const double records = find ? double(rc_hit_records(s)) : 0.0, per = find ? 1.0 : 0.0;
    d.slots = {{"probe_hits", Access::write, hits},
               {"rc_cells", Access::read_write, cells,
                Touched{records, {{"probing_collisions", per}}, sizeof(glsl::RcCell), false}},
               {"rc_active", Access::write, active, Touched{0, {{"cells_queued", per}}, sizeof(uint32_t), true}},
               {"rc_counters", Access::write, counters},
               {"rc_counters", Access::read_prev},  // written: zeroed for the next frame
               {"rc_pending", Access::write, pending,
                Touched{0, {{"hits_pending_round1", per}}, 2 * sizeof(uint32_t), true}}};
    d.work = {{"probes", kProbesPerCascade}, {"rays", double(kProbesPerCascade) * rays}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const DeviceInfo& info = ctx.gpu.info();
    if (!info.subgroup_ballot || !info.subgroup_arithmetic)
      throw std::runtime_error(
          "probe_trace: the device lacks compute subgroup ballot/arithmetic operations "
          "(VkPhysicalDeviceSubgroupProperties), which the cache insertion (rc_insert.glsl) needs");
    const RadianceCacheSettings& r = ctx.settings.params<RadianceCacheSettings>();
    ProbeTracePush push{make_rc_params(ctx.settings, ctx.frame),
                        {rc_active_capacity(ctx.settings), 0, rc_hit_records(ctx.settings), 0}};
    record_compute(ctx, {.shader = "probe_trace.comp",
                         .groups_x = div_up(rc_hit_records(ctx.settings), kProbeTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kProbeTraceSpecAlpha, ctx.scene.features().has(Feature::alpha_tested)},
                                            {kProbeTraceSpecGroupCounts, rc_group_counts(info, r) ? 1u : 0u},
                                            {kProbeTraceSpecFind, r.insertion_find == 0 ? 1u : 0u}},
                         .buffers = {{kProbeTraceBindHits, "probe_hits"},
                                     {kProbeTraceBindCells, "rc_cells"},
                                     {kProbeTraceBindActive, "rc_active"},
                                     {kProbeTraceBindCounters, "rc_counters"},
                                     {kProbeTraceBindNextCounters, "rc_counters", true},
                                     {kProbeTraceBindPending, "rc_pending"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_trace_pass() { return std::make_unique<ProbeTracePass>(); }

}  // namespace gib
