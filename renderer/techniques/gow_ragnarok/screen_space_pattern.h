// CPU mirror of gow_screen_space.glsl's sampling pattern (ssdo, ssgi): the per-pixel turn and
// first step from the frame's hash, and the cosine-weighted golden-angle directions around a
// normal. tests/test_gow_ssdo.cpp checks them against known answers and against the GLSL.
#pragma once
#include <cstdint>

#include "renderer/scene/math.h"

namespace gib {

struct SsRotation {
  float turn;    // whole turns of the pattern, [0, 1)
  float jitter;  // the march's first step, in steps, [0, 1)
};
// gib_rng(seed, frame, pixel, stream) of hash.glsl, its first two numbers.
SsRotation ss_rotation(uint32_t seed, uint32_t frame, uint32_t px, uint32_t py, uint32_t stream);

// Direction i of n around `normal` (unit), turned by `turn` whole turns.
Vec3 ss_direction(uint32_t i, uint32_t n, float turn, Vec3 normal);

}  // namespace gib
