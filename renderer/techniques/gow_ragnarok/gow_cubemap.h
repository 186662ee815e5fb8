// CPU mirror of gow_ragnarok/include/gow_cubemap.glsl: the reflection cube map's addressing
// (faces side by side in one 6N x N image) and Lagarde's box projection, for the tests.
#pragma once
#include <cstdint>

#include "renderer/scene/math.h"

namespace gib {

Vec3 gow_cube_dir(uint32_t face, float s, float t);                   // not normalised
uint32_t gow_cube_face(Vec3 d, float& s, float& t);                   // inverse of gow_cube_dir
void gow_cube_texel(Vec3 d, uint32_t n, int32_t& x, int32_t& y);      // texel of the 6N x N image
float gow_box_exit(Vec3 x, Vec3 d, Vec3 bmin, Vec3 bmax);             // distance to the far side
Vec3 gow_box_project(Vec3 x, Vec3 d, Vec3 bmin, Vec3 bmax, Vec3 capture);

}  // namespace gib
