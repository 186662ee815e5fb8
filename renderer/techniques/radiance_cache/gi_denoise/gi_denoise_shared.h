#ifndef GIB_GI_DENOISE_SHARED_H
#define GIB_GI_DENOISE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kDenoiseGroup, 8)
GIB_CONST(uint, kDenoiseBindNormal, 8)     // gbuffer_normal (full res)
GIB_CONST(uint, kDenoiseBindPosition, 9)   // gbuffer_position (full res)
GIB_CONST(uint, kDenoiseBindHit, 10)       // gather_hit_distance
GIB_CONST(uint, kDenoiseBindInR, 11)       // horizontal: gather_sh_*; vertical: gi_denoise_tmp_*
GIB_CONST(uint, kDenoiseBindInG, 12)
GIB_CONST(uint, kDenoiseBindInB, 13)
GIB_CONST(uint, kDenoiseBindOutR, 14)      // horizontal: gi_denoise_tmp_*; vertical: gi_sh_*
GIB_CONST(uint, kDenoiseBindOutG, 15)
GIB_CONST(uint, kDenoiseBindOutB, 16)
GIB_CONST(uint, kDenoiseBindInDirect, 17)  // horizontal: gather_direct; vertical: gi_denoise_tmp_direct
GIB_CONST(uint, kDenoiseBindOutDirect, 18) // horizontal: gi_denoise_tmp_direct; vertical: gi_direct
GIB_CONST(uint, kDenoiseSpecTiled, 0)      // bool: taps preloaded into group-shared memory
GIB_CONST(uint, kDenoiseSpecTileTexels, 1) // the tile's texels (1 for the per-tap kernel)
GIB_CONST(uint, kDenoiseSpecFused, 2)      // bool: both directions in one dispatch (tiled only)
// The tiled kernel's largest radius: its tile is kDenoiseGroup x (kDenoiseGroup + 2 x radius)
// texels of 60 bytes (at most 11.3 KB, under Vulkan's guaranteed 16 KB of shared memory); a
// larger radius runs the per-tap kernel.
GIB_CONST(uint, kDenoiseTileMaxRadius, 8)
// The fused kernel's largest radius: its tile is (kDenoiseGroup + 2 x radius)^2 texels (at most
// 15 KB); each of its threads keeps at most 2 horizontal results. A larger radius runs the two
// dispatches.
GIB_CONST(uint, kDenoiseFusedMaxRadius, 4)
// Edge-stopping weights of a tap q for the centre g (gather pixels; geometry from their
// representative full-res pixels g * divisor + divisor / 2, as final_gather):
//   normal    pow(max(0, dot(n_g, n_q)), kDenoiseNormalPower)
//   depth     exp(-rel / kDenoiseDepthSigma), rel = |dot(n_g, p_q - p_g)| / depth_g (distance of
//             the tap from the centre's tangent plane, relative to the centre's view distance)
//   hit       exp(-(dh / kDenoiseHitSigma)^2), dh = |h_q - h_g| / max(h_q, h_g)
//   spatial   exp(-k^2 / (2 sigma^2)), sigma = radius / 2
// The gather's direct part (gather_direct) takes the geometry weights only (normal, depth,
// spatial): a weight that depends on the hit distance depends on the sample's value (misses
// carry the sky, hits the bounce), which pulls the mean towards the centre's class and biases
// it towards the majority class (an emissive panel's direct light read +2.8%).
GIB_CONST(float, kDenoiseNormalPower, 32.0)
GIB_CONST(float, kDenoiseDepthSigma, 0.02)
GIB_CONST(float, kDenoiseHitSigma, 1.0)
struct DenoisePush {
  int axis_x, axis_y;  // (1, 0) horizontal, (0, 1) vertical
  uint radius;         // taps either side
  uint divisor;        // gather divisor: 1, 2 or 4
  uint nan_guards;     // 1: taps with a non-finite weight or value are skipped
  uint hit_weight;     // 1: the SH taps also weigh hit-distance similarity (the seed's); 0: geometry only
  uint pad1, pad2;
};
GIB_SHARED_END
#endif
