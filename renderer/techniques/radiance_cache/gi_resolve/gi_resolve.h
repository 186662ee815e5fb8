// gi_resolve: the AOVs gi_irradiance and gi_direct_irradiance (RGBA32F, irradiance / pi in
// absolute units; 0 on sky pixels): this frame's gi_history and gi_history_direct / P_now (word
// 0 of `exposure`). Nothing in the frame reads them (gi_composite decodes the history itself),
// so the graph culls this pass unless they are asked for (tests, --dump).
// Slots: reads gi_history, gi_history_direct, exposure; writes gi_irradiance,
// gi_direct_irradiance. One kernel per history format (gi_resolve_<format>.comp).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_gi_resolve_pass();
}
