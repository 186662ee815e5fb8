// Tangent-space normal maps: the CPU mirror of renderer/shaders/include/normal_map.glsl (the
// frame, the glTF convention and the fallbacks are described there). Same operation order; the
// GPU's sqrt and division are not correctly rounded, so the two agree to a few ulps, not bit for
// bit (tests/test_normal_map_gpu.cpp).
#pragma once
#include "renderer/scene/math.h"

namespace gib {

// n: unit shading normal of a triangle with positions p[3] and uvs t[3]; texel: the normal map's
// linear rgb in [0, 1]; scale: glTF normalTexture.scale.
Vec3 apply_normal_map(Vec3 n, const Vec3 p[3], const Vec2 t[3], Vec3 texel, float scale);

// The texel that encodes unit tangent-space normal m (x along T, y along B, z along n), before
// 8-bit quantisation: (m + 1) / 2. For content generators and tests.
Vec3 encode_tangent_normal(Vec3 m);

}  // namespace gib
