// Octahedral mapping of unit vectors to [0,1]^2 and the texel layout of octahedral tiles with
// a one-texel border: the CPU mirror of renderer/shaders/include/octahedral.glsl.
//
// Map: p = n.xy / (|n.x| + |n.y| + |n.z|); the lower hemisphere (n.z < 0) is folded over the
// diagonals: p = (1 - |p.yx|) * sign_not_zero(p); uv = p * 0.5 + 0.5. +z is the square's
// centre, -z its four corners, the equator the inner diamond |p.x| + |p.y| = 1.
// Decode inverts it and normalises. These use division and sqrt, which GPUs may round
// differently from the CPU, so CPU and GPU agree to a few ulp, not bit for bit.
//
// Tiles: an N x N interior (texel centres at uv = (i + 0.5) / N) framed by a one-texel border,
// (N + 2)^2 texels, tile-local texel (0,0) the top-left border corner, interior 1..N. A border
// texel copies the interior texel that continues the map across the square's edge: the edge
// u = 0 is glued to itself mirrored about its midpoint (direction(0, v) == direction(0, 1 - v)),
// so left/right border texel (0 or N+1, y) copies (1 or N, N + 1 - y), top/bottom border
// (x, 0 or N+1) copies (N + 1 - x, 1 or N), and each corner copies the diagonally opposite
// interior corner. Bilinear taps straddling a tile edge then blend the right directions.
#pragma once
#include "renderer/scene/math.h"

namespace gib::codecs {

Vec2 oct_encode(Vec3 n);   // n need not be normalised (not zero); returns [0,1]^2
Vec3 oct_decode(Vec2 uv);  // unit vector

struct Texel {
  int x = 0, y = 0;
  friend bool operator==(Texel a, Texel b) { return a.x == b.x && a.y == b.y; }
};
// Tile-local texel (0..interior+1 per axis) -> the tile-local texel holding its value
// (itself for interior texels).
Texel oct_border_source(Texel t, int interior);
// Direction -> tile-local continuous texel coordinate (texel centres at integer + 0.5), for
// bilinear sampling inside a bordered tile: 1 + uv * interior.
Vec2 oct_tile_coord(Vec3 n, int interior);
// Direction at the centre of interior texel (x, y), 1 <= x, y <= interior.
Vec3 oct_texel_direction(Texel t, int interior);

}  // namespace gib::codecs
