// radiance-cache's stages for error attribution (harness/attribution/, `gibench attribute`) and
// their oracles, written over the stage's outputs by graph overrides (no pass changes):
//   radiance_cache      light_grid, probe_trace,       none yet (cells sit in a hash table whose
//                       radiance_cache_update,         slots differ between seeds, so a seed mean
//                       radiance_cache_shade           is not defined; the exact one needs the path
//                                                      tracer's radiance at each cell)
//   irradiance_volumes  irradiance_volume_update       converged: the seed renders' mean
//                                                      probe_irradiance (RGB9E5, re-encoded) and
//                                                      probe_visibility (half moments)
//   final_gather        exposure, final_gather         none yet (the exact one needs the path
//                                                      tracer's radiance along each gather ray)
//   denoise             gi_denoise                     the seed renders' mean of its input
//                                                      (gather_sh_r/g/b, gather_direct), each read
//                                                      taken to absolute units by its own
//                                                      pre-exposure P and written at their mean P,
//                                                      which it writes into `exposure` after the
//                                                      exposure pass (the whole frame at that P)
//   upscale             gi_upscale, gi_composite,      exact: the reference's indirect_diffuse in
//                       gi_resolve                     gi_composite's indirect_diffuse, and the
//                                                      seeds' mean direct_radiance plus it in its
//                                                      final_color (next frame's gather reads it)
#pragma once
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib {

std::vector<TechniqueStage> radiance_cache_stages();

}  // namespace gib
