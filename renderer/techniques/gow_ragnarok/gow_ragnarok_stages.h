// gow-ragnarok's stages for error attribution (harness/attribution/, `gibench attribute`) and
// their oracles, written over the stage's outputs by graph overrides (no pass changes):
//   direct       shadow_maps .. shadows_contact_hardening,  exact: the reference's `direct` AOV
//                direct_lighting                            (direct_light, which SSDO and SSGI
//                                                           read as their bounce source)
//   ssgi         ssdo, ssgi, ssdo_ssgi                      exact: the reference's indirect_diffuse
//                                                           (ssgi_indirect's colour; its alpha, the
//                                                           accumulation's frame count, kept). The
//                                                           combined pass only: rows with
//                                                           ss_combined 0 run ssgi instead and this
//                                                           oracle is not written there. Not the
//                                                           ray-traced-visibility oracle (the march
//                                                           with BVH visibility), which would
//                                                           separate the screen's limits from the
//                                                           one-bounce limit: not built
//   reflections  cubemap_capture, reflections_rt_cubemap,   none (not part of indirect_diffuse)
//                reflections_resolve
#pragma once
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib {

std::vector<TechniqueStage> gow_ragnarok_stages();

}  // namespace gib
