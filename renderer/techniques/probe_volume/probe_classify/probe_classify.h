// probe_classify: indoor / outdoor classification of the selected probes (AC Shadows RTGI,
// "Probe selection: classify indoor/outdoor" and "Light leaks: indoor volumes"): a probe is
// indoor when its position (after a pending relocation) lies in one of the scene's indoor
// volumes (scene key "indoor_volumes": axis-aligned boxes, cases/scenes/README.md). Samplers
// blend only probes of the sampled point's class (include/pv_sample.glsl), each face of a
// translucent surface classified on its own side; indoor_classes 0: every probe and point
// outdoor (the control). Needs the scene feature indoor_volumes: culled without it (every
// probe then stays outdoor, as every point).
// Slots: read probe_selection; read_write probe_state.
// Limits: boxes only (the seed reuses the planes of its baked GI); no terrain test (the seed's
// caves keep probes valid under terrain with this flag).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_classify_pass();
}
