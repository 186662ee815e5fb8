// direct_aov: gow-ragnarok's `direct` AOV in the combined form (option ss_combined 1):
// gow_direct = direct_light + ssdo_local_light (the local lights through SSDO; direct_light alone
// where the scene has none). Nothing in the frame reads it: ssdo_ssgi writes the output
// (gow_radiance) from the same two terms itself, so the graph runs this pass only when the AOV
// is asked for (a case row comparing `direct`, a dump, bench, which times it as AOV-only).
// The separate form's ssgi pass writes gow_direct itself (this pass is then culled).
// Slots: reads direct_light (rgba32f), ssdo_local_light (rgba16f, where the scene has unshadowed
// local lights); writes gow_direct (rgba32f).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_direct_aov_pass();
}
