// attribute_interpolate: per pixel of the visibility buffer, the triangle attributes the later
// compute passes need, stored in the seed's formats (DOOM: The Dark Ages, "Deferred Attribute
// Interpolation"; the math is the perspective-correct plane intersection of software
// rasterisers):
//   vis_bary           RG16F    barycentrics (b, c) at the pixel centre
//   vis_bary_deriv     RGBA16UI ddx(b), ddx(c), ddy(b), ddy(c) as binary16 clamped to ]-2, 2[,
//                               bit 14 of each carrying a flag: front facing, normal z sign,
//                               tangent z sign, bitangent sign (codecs/bary_deriv.h)
//   vis_tangent_frame  RGBA16F  world normal x, y (facing the camera) and world tangent x, y
// Reads: vbuffer. Sky pixels get zeros. The derivatives come from the rays through the next
// pixel in x and y intersected with the same triangle's plane, so they exist across its edges.
// Limits: the half-float barycentrics place the position within ~5e-4 of an edge length in the
// triangle's plane (deferred_texturing takes the position from the camera ray and the plane);
// the normal's z is rebuilt from x, y (coarse near the xy plane).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_attribute_interpolate_pass();
}
