// visibility: rasterises every triangle of the flattened scene (no culling: surfaces are
// double-sided) into a 64-bit visibility buffer (R32G32_UINT: triangle id + 1, instance id)
// and a D32 depth buffer. Alpha-tested materials discard in the fragment shader with the
// same mask the tracer uses; stochastic opacity uses a hash of (pixel, frame).
// Slots: writes vbuffer (rg32_uint), depth (d32_float).
// Seed: DOOM: The Dark Ages "Visibility Buffer and Deferred Rendering" talk, "Visibility Buffer" (64-bit ids, then compute).
// Limits: one draw of all triangles (no instancing, no GPU culling): scenes here are small.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_visibility_pass();
}
