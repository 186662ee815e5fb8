// path_trace_resolve: divides each of the path tracer's running sums by its sample count,
// giving the reference AOVs. One dispatch per AOV (scopes `path_trace_resolve/<aov>`); an AOV
// nobody requested is still resolved (cheap), but the pass as a whole is culled when no
// reference AOV is requested.
// Slots: reads pt_radiance_sum, pt_direct_sum, pt_indirect_sum; writes radiance, direct,
// indirect_diffuse (rgba32f).
// Seed: none (the ground truth; docs/architecture.md "Techniques").
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_path_trace_resolve_pass();
}
