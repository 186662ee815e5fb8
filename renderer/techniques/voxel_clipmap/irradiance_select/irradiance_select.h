// irradiance_select: which irradiance cells are relit this frame (Enlisted GDC 2019, 3.1):
// every cell ages by one frame; visible cells (in the view frustum) pass when
// age x random > P, P adapted from the previous frame's count of passing cells (halved to
// doubled towards the queues' total capacity). Queues: A' (cells whose box holds voxels with
// opacity and that were never relit: taken whether they pass or not), A (cells with geometry
// that passed; A' and A together at most queue_a: "first N cells in QueueA, where N is
// capacity(QueueA) - occupied(QueueA')"), B (empty cells that passed, at most queue_b). With
// geometry_light, cells with geometry out of view (never relit, or passing) take what capacity
// of queue A the visible cells leave: they light the voxels scene_voxel_light keeps lit behind
// the camera (the seed relights visible cells only; its unseen walls are never lit). The
// result is one list, A' then A then B then A out of view, and the indirect arguments of irradiance_relight (one
// workgroup per cell). One workgroup appends in cell order with subgroup ballots, so the
// selection is the same on every run. select_per_queue 1 keeps two thresholds, P for cells
// with geometry (towards queue A's capacity less A') and P for empty cells (towards queue B's).
// Slots: read_write voxel_clip_state, irradiance_cell_state; read scene_voxel_data;
// writes irradiance_queue.
// Limits: no hierarchical-Z occlusion test (frustum only); one workgroup walks every cell; with
// one P (select_per_queue 0, the default) the far more numerous empty cells set it and cells
// with geometry can starve for frames (voxel_clipmap.md, "Limits").
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_irradiance_select_pass();
}
