#include "renderer/techniques/radiance_cache/probe_trace/probe_trace.h"

#include <fmt/format.h>

#include <cstddef>

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
    ResourceDesc hits{Format::buffer, SizeRule::buffer};
    hits.bytes = uint64_t(kProbesPerCascade) * rays * sizeof(glsl::ProbeHit);
    hits.values = non_negative_values().layout(sizeof(glsl::ProbeHit) / 4, offsetof(glsl::ProbeHit, distance) / 4, 1);
    d.slots = {{"probe_hits", Access::write, hits}};
    d.work = {{"probes", kProbesPerCascade}, {"rays", double(kProbesPerCascade) * rays}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    ProbeTracePush push{make_rc_params(ctx.settings, ctx.frame)};
    uint32_t threads = kProbesPerCascade * ctx.settings.params<RadianceCacheSettings>().rays_per_probe;
    record_compute(ctx, {.shader = "probe_trace.comp",
                         .groups_x = div_up(threads, kProbeTraceGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kProbeTraceSpecAlpha, ctx.scene.features().has(Feature::alpha_tested)}},
                         .buffers = {{kProbeTraceBindHits, "probe_hits"}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_probe_trace_pass() { return std::make_unique<ProbeTracePass>(); }

}  // namespace gib
