// irradiance_relight: relights the queued irradiance cells (Enlisted GDC 2019, 3 and 3.1): one
// workgroup per cell (an indirect dispatch over irradiance_select's list), one thread per ray
// (rays_per_cell: 32-256), rays spread over the sphere (a Fibonacci lattice jittered per cell
// and frame) from the cell centre, brute-force marched through the scene voxels (vc_march: no
// cone tracing, so thin walls are not skipped; semi-transparent voxels accumulate and extinct);
// what passes every voxel takes the sky. Each of the six ambient-cube directions gets the
// cosine-weighted mean of its hemisphere's rays, bounce (voxel hits) and sky (misses) apart;
// the cell's old value is blended towards it with weight min(1, age / history_frames) (1 for a
// cell never relit): the seed's temporal accumulation weighted by age.
// Slots: read irradiance_queue; read_write voxel_clip_state and scene_voxel_data (read only:
// declared read_write so the graph orders this pass before scene_voxel_feed rewrites them),
// irradiance_x, irradiance_y, irradiance_z, irradiance_cell_state.
// Limits: specular probes for misses are not modelled (the sky only, the seed's fallback).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_irradiance_relight_pass();
}
