// probe_relocate: moves probes out of or away from geometry (AC Shadows RTGI, "Relocation"),
// for every probe traced this frame. Inside geometry: more than 25% of its hits are back faces
// of opaque surfaces within one spacing (a room modelled as a box seen from inside shows back
// faces everywhere, farther away: our surfaces are two-sided). Too near: its nearest hit is
// closer than 0.2 spacings. Such a probe moves towards its deepest texel (a miss: the full
// range) by half that depth, its offset kept within 0.45 spacings of the cell centre per axis;
// the new offset is pending until the probe is re-traced there (flag retrace: probe_select
// takes such probes first among the G-buffer refreshes; probe_gbuffer applies it), so its
// G-buffer always matches the position it was traced from. A probe inside geometry that cannot
// move is disabled (samplers skip it); a later trace that finds it outside enables it again.
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
