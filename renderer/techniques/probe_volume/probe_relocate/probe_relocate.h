// probe_relocate: moves probes out of or away from geometry (AC Shadows RTGI, "Relocation"),
// for every probe traced this frame. Inside geometry: more than 25% of its hits are back faces
// of opaque surfaces; too near: its nearest hit is closer than 0.2 spacings. Such a probe moves
// towards its deepest texel (a miss: the full range) by half that depth, its offset kept within
// 0.45 spacings of the cell centre per axis; a probe that moved is re-traced next frame
// (flag retrace: probe_select takes it as new). A probe inside geometry that cannot move is
// disabled (samplers skip it); a later trace that finds it outside enables it again.
// relocation 0: probes stay put and none is disabled (the control).
// Slots: read probe_selection, probe_gb_depth; read_write probe_state.
// Limits: no terrain test (the seed moves probes above the terrain and disables deep ones:
// we have no terrain); the move is one step per trace, not a search.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_relocate_pass();
}
