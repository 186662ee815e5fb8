#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/shadow_minmax/shadow_minmax_shared.h"

layout(local_size_x = kShadowGroup, local_size_y = kShadowGroup) in;
layout(set = 0, binding = kShadowBindMap, r32f) uniform readonly image2D shadow_map;
layout(set = 0, binding = kMinMaxBindTiles, rg32f) uniform writeonly image2D tiles_out;

// Min and max depth of each kShadowMinMaxTile^2 block of the shadow-map atlas (cascade squares
// are whole blocks, so no block straddles two cascades).
void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, imageSize(tiles_out)))) return;
  float lo = 1.0, hi = 0.0;
  for (int y = 0; y < int(kShadowMinMaxTile); ++y)
    for (int x = 0; x < int(kShadowMinMaxTile); ++x) {
      float d = imageLoad(shadow_map, t * int(kShadowMinMaxTile) + ivec2(x, y)).x;
      lo = min(lo, d);
      hi = max(hi, d);
    }
  imageStore(tiles_out, t, vec4(lo, hi, 0.0, 0.0));
}
