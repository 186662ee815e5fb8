// shadow_minmax: a downsampled min/max depth map of the shadow-map atlas (one texel per
// kShadowMinMaxTile^2 texels), dilated by the area-light radius so that a receiver can tell
// from one read whether every tap of its filter is lit or shadowed, and how far its ray march
// can reach an occluder. Kernels: shadow_minmax_tiles (per block), then shadow_minmax twice
// (dilate along x, then y: separable, linear in the radius).
// Slots: reads shadow_map; writes shadow_minmax_tiles, shadow_minmax_rows, shadow_minmax
// (rg32_float, fixed).
// Seed: God of War Ragnarök, "Contact Hardening Shadows" ("create a downsampled min/max shadow
// map, dilate according to shadow filter radius; early out if fully in or out of shadow;
// tighten range of ray trace").
// Limits: dilation in whole blocks and over a square (over-dilates by up to a block and to the
// square's corners: conservative, fewer early outs).
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_shadow_minmax_pass();
}
