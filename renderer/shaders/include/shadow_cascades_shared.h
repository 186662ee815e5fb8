// Shared by C++ and GLSL: the cascaded sun shadow map (renderer/passes/shadow_maps/), its
// push constants, bindings and limits. Every shadow pass derives the cascades from the frame
// constants (camera, sun) and ShadowPush, through shadow_cascades.glsl; shadow_cascades.h mirrors
// that on the CPU.
#ifndef GIB_SHADOW_CASCADES_SHARED_H
#define GIB_SHADOW_CASCADES_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kShadowMaxCascades, 4)
GIB_CONST(uint, kShadowMaxTaps, 32)      // rays / PCF taps per pixel (the seed's 32-bit ray mask)
GIB_CONST(uint, kShadowGroup, 8)         // 8x8 threads
GIB_CONST(uint, kShadowMinMaxTile, 8)    // shadow-map texels per min/max texel (each side)
// Bindings after the scene bundle.
GIB_CONST(uint, kShadowBindMap, 8)       // r32f: light-space depth per texel, cascades side by side
GIB_CONST(uint, kShadowBindMinMax, 9)    // rg32f: dilated min, max depth per kShadowMinMaxTile^2 texels
GIB_CONST(uint, kShadowBindPosition, 10) // gbuffer_position (rgba32f)
GIB_CONST(uint, kShadowBindNormal, 11)   // gbuffer_normal (rgba16f)
GIB_CONST(uint, kShadowBindOut, 12)      // r32f sun visibility in [0, 1]

// The cascade set (both kernels and the raster read it). 80 bytes.
struct ShadowCascadePush {
  vec4 splits;      // far view distance (m) of cascade 0..3; cascade i covers (splits[i-1], splits[i]]
  vec4 params;      // x: cascades, y: resolution (texels per side of one cascade), z: caster range (m
                    //   towards the sun beyond a cascade's sphere), w: near view distance (m)
  vec4 area;        // x: filter radius (m, light space) of the area light; y: march distance (m);
                    //   z: depth bias (m); w: normal offset (texels)
  uvec4 counts;     // x: taps, y: march steps, z: cascade to rasterise (shadow_maps) or dilation axis
                    //   (shadow_minmax: 1 x, 0 y), w: use min/max (1)
  vec4 blend;       // x: seam band, a fraction of a cascade's width: within it of the cascade's edge
                    //   the filters blend into the next cascade (0: off); yzw unused
};
GIB_SHARED_END
#endif
