// probe-volume's stages for error attribution (harness/attribution/, `gibench attribute`) and
// their oracles, written over the stage's outputs by graph overrides (no pass changes):
//   probes       probe_select .. probe_relocate  converged: the seed renders' mean probe_irradiance
//                                                 and probe_radiance (same half texels, no one
//                                                 seed's ray noise; representation and bias kept)
//   pixel_trace  screen_trace, world_trace,       none yet (the exact one needs the path tracer's
//                hit_lighting                     radiance along each pixel's rays)
//   denoise      pixel_denoise                    the mean of the seed renders of its input
//                                                 (pixel_sh decoded: Y0, Y1, Co, Cg)
//   upscale      pixel_upscale                    exact: the reference's indirect_diffuse divided
//                                                 by the G-buffer albedo (composite multiplies back)
#pragma once
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib {

std::vector<TechniqueStage> probe_volume_stages();

}  // namespace gib
