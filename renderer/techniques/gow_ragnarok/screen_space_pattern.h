// CPU mirror of gow_ss_pattern.glsl: the screen-space passes' sampling pattern (ssdo, ssgi,
// ssdo_ssgi): the per-pixel turn and first step from the frame's hash, and the cosine-weighted
// golden-angle directions around a normal; and the encoding of ssdo_ssgi's half-size surfaces
// (gow_ss_pack_surface). tests/test_gow_ssdo.cpp checks them against known answers and against
// the GLSL.
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

// One texel of ssdo_ssgi's ss_surfaces (rg32ui): a 2x2 block's surface for the marches' depth
// tests. Word 0: the distance from the camera (0: no surface), the sign bit set where the normal
// is unusable (NaN or shorter than 1/2); word 1: the normal, octahedral at 15 bits per axis
// (bits 2-16, 17-31), and the block's pixel x + 2 y (bits 0-1).
struct SsSurface {
  float dist = 0;
  bool plane = false;  // the normal is usable
  Vec3 normal;         // unit where `plane`
  uint32_t pixel = 0;  // 0..3
};
void ss_pack_surface(float dist, Vec3 n, uint32_t pixel, uint32_t out[2]);
SsSurface ss_unpack_surface(const uint32_t in[2]);

}  // namespace gib
