// reflections_resolve: the full-resolution temporal resolve of "Raytraced Cubemaps" (the seed's
// "Resolve: 1.36ms, full-res", after Stachowiak 2015): each pixel takes its 2x2 block's
// half-resolution sample (reflection_trace) and averages it with its own history, reprojected
// with last frame's camera, over at most `reflection_history` frames (a running mean: a static
// view converges to the lobe's average). History is dropped where the reprojected pixel leaves
// the screen, where it was not glossy, and (nan_guards) where it is not finite.
// Slots: read reflection_trace, gbuffer_position; read_prev reflection; write reflection
// (rgba32f, persistent: rgb the lobe's reflected radiance, a the frames averaged).
// Needs: glossy.
// Limits: no neighbourhood filter (the seed's resolve also reuses neighbours' rays with their
// BRDF weights); pixels on a glossy edge whose block's traced pixel is not glossy read 0 that
// frame; no disocclusion test beyond the screen bounds.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_reflections_resolve_pass();
}
