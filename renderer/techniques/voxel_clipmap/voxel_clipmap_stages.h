// voxel-clipmap's stages for error attribution (harness/attribution/, `gibench attribute`) and
// their oracles, written over the stage's outputs by graph overrides (no pass changes):
//   scene_voxels  scene_voxels, scene_voxel_invalidate,   none yet (the exact one needs the path
//                 scene_voxel_fill                        tracer's radiance leaving each voxel)
//   irradiance    irradiance_clipmap, irradiance_select,  converged: the seed renders' mean
//                 irradiance_relight                      irradiance cubes (irradiance_x/y/z, the
//                                                         last frame's: static scenes)
//   voxel_light   scene_voxel_feed, scene_voxel_light     none yet (as scene_voxels; these light
//                                                         the voxels the next frame's relight reads)
//   shade         irradiance_shade                        exact: the reference's indirect_diffuse
//                                                         over the G-buffer albedo (gi_irradiance)
#pragma once
#include <vector>

#include "renderer/techniques/technique.h"

namespace gib {

std::vector<TechniqueStage> voxel_clipmap_stages();

}  // namespace gib
