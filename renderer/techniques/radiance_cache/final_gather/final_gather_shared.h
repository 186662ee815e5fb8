// final_gather <-> C++: bindings, push constants and the gather-pixel convention that
// gi_denoise and gi_upscale repeat (they read only radiance_cache_shared.h and their own
// headers, so the convention is restated there: the representative full-res pixel of gather
// pixel g is g * divisor + divisor / 2, clamped to the render size).
#ifndef GIB_FINAL_GATHER_SHARED_H
#define GIB_FINAL_GATHER_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kGatherGroup, 8)
GIB_CONST(uint, kGatherBindNormal, 8)        // gbuffer_normal (rgba16f)
GIB_CONST(uint, kGatherBindPosition, 9)      // gbuffer_position (rgba32f, w = distance; 0 sky)
GIB_CONST(uint, kGatherBindPrevPosition, 10) // last frame's gbuffer_position
GIB_CONST(uint, kGatherBindPrevColor, 11)    // last frame's final_color (rgba32f)
GIB_CONST(uint, kGatherBindProbeIrradiance, 12)  // probe_irradiance (r32ui RGB9E5)
GIB_CONST(uint, kGatherBindProbeVisibility, 13)  // probe_visibility (rg16f)
GIB_CONST(uint, kGatherBindCells, 14)        // rc_cells (RcCell[])
GIB_CONST(uint, kGatherBindStats, 15)        // gather_stats (uint[4])
GIB_CONST(uint, kGatherBindShR, 16)          // gather_sh_r/g/b (rgba16f: L0, L1)
GIB_CONST(uint, kGatherBindShG, 17)
GIB_CONST(uint, kGatherBindShB, 18)
GIB_CONST(uint, kGatherBindHitDistance, 19)  // gather_hit_distance (r32f)
GIB_CONST(uint, kGatherBindExposure, 20)     // exposure (float[4], exposure_shared.h: P_now at 0)
GIB_CONST(uint, kGatherBindDirect, 21)       // gather_direct (rgba16f: rgb the direct part, a 0)
GIB_CONST(uint, kGatherBindVbuffer, 22)      // vbuffer (rg32ui): the face normal rays leave along
GIB_CONST(uint, kGatherExposureNow, 0)
GIB_CONST(uint, kGatherSpecAlpha, 0)

// gather_stats: which cache answered each ray this frame.
GIB_CONST(uint, kGatherStatScreen, 0)
GIB_CONST(uint, kGatherStatWorld, 1)
GIB_CONST(uint, kGatherStatVolume, 2)
GIB_CONST(uint, kGatherStatSky, 3)
GIB_CONST(uint, kGatherStatCount, 4)

// Hit distance written for rays that escape to the sky (metres); 0 marks a gather pixel with
// no surface (its representative pixel is sky).
GIB_CONST(float, kGatherMissDistance, 1000.0)
// Screen cache: the hit is unoccluded in last frame's image when its view depth under
// prev_view_proj and that of last frame's G-buffer sample at its pixel agree within this
// relative tolerance.
GIB_CONST(float, kGatherScreenDepthTolerance, 0.05)
// Lower bound on cos(theta) in the 1/pdf weight pi / cos(theta) of the L1 projection: bounds a
// sample's weight (50x); P(cos < 0.02) = 0.0004 under the cosine pdf.
GIB_CONST(float, kGatherMinCos, 0.02)

struct GatherPush {
  uint divisor;       // gather divisor: 1, 2 or 4
  uint screen_cache;  // 0: skip the screen cache (first frame: last frame's image is empty)
  uint sky;           // 1: the gather's direct part (sky on a miss, a hit's emission) is kept;
                      // 0 (direct_lighting traces them, sky_rays > 0): it is dropped, no double count
  uint pad;
};
GIB_SHARED_END
#endif
