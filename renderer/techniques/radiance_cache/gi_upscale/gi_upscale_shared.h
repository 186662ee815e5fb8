#ifndef GIB_GI_UPSCALE_SHARED_H
#define GIB_GI_UPSCALE_SHARED_H
#include "frame_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kUpscaleGroup, 8)
GIB_CONST(uint, kUpscaleBindNormal, 8)        // gbuffer_normal
GIB_CONST(uint, kUpscaleBindPosition, 9)      // gbuffer_position
GIB_CONST(uint, kUpscaleBindPrevNormal, 10)   // last frame's gbuffer_normal
GIB_CONST(uint, kUpscaleBindPrevPosition, 11) // last frame's gbuffer_position
GIB_CONST(uint, kUpscaleBindShR, 12)          // gi_sh_r/g/b (gather resolution)
GIB_CONST(uint, kUpscaleBindShG, 13)
GIB_CONST(uint, kUpscaleBindShB, 14)
GIB_CONST(uint, kUpscaleBindPrevHistory, 15)  // last frame's gi_history
GIB_CONST(uint, kUpscaleBindPrevFrames, 16)   // last frame's gi_history_frames
GIB_CONST(uint, kUpscaleBindHistory, 17)      // gi_history (format: history_format)
GIB_CONST(uint, kUpscaleBindFrames, 18)       // gi_history_frames (r32f: n)
GIB_CONST(uint, kUpscaleBindExposure, 20)     // exposure (float[4], exposure_shared.h: P_now, P_prev)
GIB_CONST(uint, kUpscaleBindDirect, 21)             // gi_direct (gather resolution, rgb)
GIB_CONST(uint, kUpscaleBindPrevHistoryDirect, 22)  // last frame's gi_history_direct
GIB_CONST(uint, kUpscaleBindHistoryDirect, 23)      // gi_history_direct (format: history_format)
GIB_CONST(uint, kUpscaleSpecTiled, 0)     // bool: the group's gather samples preloaded into shared memory
GIB_CONST(uint, kUpscaleSpecTileSide, 1)  // the tile's side in gather pixels (1 for the per-tap kernel)
GIB_CONST(uint, kUpscaleExposureNow, 0)
GIB_CONST(uint, kUpscaleExposurePrev, 1)
// Upscale weights of gather sample g for full-res pixel p (normal n_p, position x_p, view
// distance d_p): bilinear x pow(max(0, dot(n_p, n_g)), kUpscaleNormalPower) x
// exp(-|dot(n_p, x_g - x_p)| / (d_p * kUpscaleDepthSigma)).
GIB_CONST(float, kUpscaleNormalPower, 16.0)
GIB_CONST(float, kUpscaleDepthSigma, 0.02)
// Temporal disocclusion tests of a last-frame texel q against p (x_p reprojected with
// prev_view_proj, clip depth w_p): depth |dot(n_q, x_p - x_q)| / w_p <= kUpscaleDepthTolerance
// (relative distance from q's tangent plane) and dot(n_p, n_q) >= kUpscaleNormalCos.
GIB_CONST(float, kUpscaleDepthTolerance, 0.05)
GIB_CONST(float, kUpscaleNormalCos, 0.9)
struct UpscalePush {
  uint divisor;        // gather divisor: 1, 2 or 4
  float max_frames;    // n_max
  uint disocclusion;   // 1: depth/normal tests reject history
  uint history_valid;  // 0 on the first frame: last frame's images were never written
  uint nan_guards;     // 1: non-finite taps, history texels and results are rejected
  uint dither;         // 1: an RGB9E5 history rounds stochastically (option dither_stores)
  uint frame;          // frame index: the dither's seed
  uint pad0;
};
GIB_SHARED_END
#endif
