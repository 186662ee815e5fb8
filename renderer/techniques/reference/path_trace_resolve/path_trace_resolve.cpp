#include "renderer/techniques/reference/path_trace_resolve/path_trace_resolve.h"

#include "renderer/techniques/reference/path_trace_resolve/path_trace_resolve_shared.h"

namespace gib {
namespace {

constexpr std::pair<const char*, const char*> kAovs[] = {
    {"pt_radiance_sum", "radiance"},
    {"pt_direct_sum", "direct"},
    {"pt_indirect_sum", "indirect_diffuse"},
    {"pt_reflection_sum", "reflection"}};

class PathTraceResolvePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "path_trace_resolve";
    for (auto [sum, out] : kAovs) {
      d.slots.push_back({sum, Access::read});
      d.slots.push_back({out, Access::write, ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())});
    }
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    for (auto [sum, out] : kAovs) {
      ctx.cmd.begin_label(std::string("path_trace_resolve/") + out);
      record_compute(ctx, {.shader = "path_trace_resolve.comp",
                           .images = {{kResolveBindSum, sum}, {kResolveBindOut, out}},
                           .groups_x = div_up(ctx.width(out), kResolveGroup),
                           .groups_y = div_up(ctx.height(out), kResolveGroup),
                           .scene = false});
      ctx.cmd.end_label();
    }
  }
};

}  // namespace

std::unique_ptr<Pass> make_path_trace_resolve_pass() { return std::make_unique<PathTraceResolvePass>(); }

}  // namespace gib
