#include "renderer/techniques/voxel_clipmap/voxel_clipmap_stages.h"

#include "renderer/techniques/stage_oracles.h"

namespace gib {

namespace {

using oracles::Bytes;

std::map<std::string, Bytes> irradiance_oracle(const OracleInputs& in) {
  return {{"irradiance_x", oracles::mean_floats(in, "irradiance_x")},
          {"irradiance_y", oracles::mean_floats(in, "irradiance_y")},
          {"irradiance_z", oracles::mean_floats(in, "irradiance_z")}};
}

}  // namespace

std::vector<TechniqueStage> voxel_clipmap_stages() {
  std::vector<TechniqueStage> s(4);
  s[0].name = "scene_voxels";
  s[0].passes = {"scene_voxels", "scene_voxel_invalidate", "scene_voxel_fill"};
  s[1].name = "irradiance";
  s[1].passes = {"irradiance_clipmap", "irradiance_select", "irradiance_relight"};
  s[1].oracle = "converged: the seed renders' mean irradiance cubes (irradiance_x/y/z)";
  s[1].after_pass = "irradiance_relight";
  s[1].seed_reads = {"irradiance_x", "irradiance_y", "irradiance_z"};
  s[1].make = irradiance_oracle;
  s[2].name = "voxel_light";
  s[2].passes = {"scene_voxel_feed", "scene_voxel_light"};
  s[3] = oracles::exact_gi_irradiance_stage("shade", {"irradiance_shade"}, "irradiance_shade");
  return s;
}

}  // namespace gib
