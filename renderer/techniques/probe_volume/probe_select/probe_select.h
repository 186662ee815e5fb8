// probe_select: the per-frame probe budget (AC Shadows RTGI, "Probe volume: Volume definition"
// and "Probe selection"). Each cascade's volume follows the camera with a forward offset
// (toroidal addressing: a slot whose cell changed is a new probe, its data invalid). Then, up
// to probe_budget probes: 1. new probes (full update, quarter resolution), in probe order;
// 2. G-buffer refreshes, gbuffer_share of the rest: first probes probe_relocate moved (their
// G-buffer is traced at the new offset), then round robin per cascade from the biggest;
// 3. relight only, the remainder, round robin per cascade (two round-robin indices per
// cascade, kept in probe_state). Counts per class each frame in probe_selection.counts.
// Slots: read_write probe_state (persistent; zeroed on the first frame: every probe new);
// writes probe_selection (header + probe indices; indirect dispatch arguments for the passes
// after it).
// Limits: cascades are not disabled when the camera moves fast (the seed can); a probe over the
// budget waits (invalid, skipped by samplers) until a later frame selects it.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_select_pass();
}
