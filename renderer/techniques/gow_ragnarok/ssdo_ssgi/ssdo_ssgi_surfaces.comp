// ssdo_ssgi, first dispatch: each 2x2 pixel block's surface (ss_surfaces, half size), the one
// pixel of the block that the march starts from and that the marches' depth tests read there.
// The pixel: the block's four in turn from a hashed start (it moves from frame to frame), the
// first with a surface. Encoding: gow_ss_pack_surface (gow_ss_pattern.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi_shared.h"
#include "frame.glsl"
#include "hash.glsl"
#include "sampling.glsl"
#include "finite.glsl"
layout(local_size_x = kSsSurfacesGroup, local_size_y = kSsSurfacesGroup) in;
layout(set = 0, binding = kSsCombinedBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kSsCombinedBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kSsCombinedBindSurfaces, rg32ui) uniform writeonly uimage2D out_surfaces;
#include "renderer/techniques/gow_ragnarok/include/gow_ss_pattern.glsl"

void main() {
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(block, imageSize(out_surfaces)))) return;
  ivec2 size = imageSize(gb_position);
  GibRng rng = gib_rng(gib_seed(), gib_frame_index(), uvec2(block), kSsCombinedStream);
  uint first = min(uint(gib_next2(rng).x * 4.0), 3u);
  uvec2 packed = uvec2(0u);  // no surface
  for (uint k = 0u; k < 4u; ++k) {
    uint j = (first + k) & 3u;
    ivec2 q = block * 2 + ivec2(j & 1u, j >> 1u);
    if (any(greaterThanEqual(q, size))) continue;
    vec4 p = imageLoad(gb_position, q);
    if (p.w != 0.0) {
      packed = gow_ss_pack_surface(length(p.xyz - gib_frame.camera_pos.xyz), imageLoad(gb_normal, q).xyz, j);
      break;
    }
  }
  imageStore(out_surfaces, block, uvec4(packed, 0u, 0u));
}
