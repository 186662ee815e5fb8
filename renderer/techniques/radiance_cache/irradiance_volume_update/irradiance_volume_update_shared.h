// irradiance_volume_update <-> C++: bindings, group size, push constants.
#ifndef GIB_IRRADIANCE_VOLUME_UPDATE_SHARED_H
#define GIB_IRRADIANCE_VOLUME_UPDATE_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kIvGroup, 8)                    // irradiance_volume_probe.comp: 8x8 threads per probe
GIB_CONST(uint, kIvMaxRays, 256)                // rays per probe held in its group-shared memory
GIB_CONST(uint, kIvRaysGroup, 64)               // irradiance_volume_rays.comp: one invocation per ray
GIB_CONST(uint, kIvConvolveGroup, 64)           // irradiance_volume_update.comp: one per tile texel
GIB_CONST(uint, kIvBindHits, 8)                 // readonly ProbeHit probe_hits[]
GIB_CONST(uint, kIvBindCells, 9)                // readonly RcCell rc_cells[]
GIB_CONST(uint, kIvBindPrevIrradiance, 10)      // last frame's probe_irradiance (r32ui RGB9E5)
GIB_CONST(uint, kIvBindPrevVisibility, 11)      // last frame's probe_visibility (rg16f)
GIB_CONST(uint, kIvBindIrradiance, 12)          // this frame's probe_irradiance
GIB_CONST(uint, kIvBindVisibility, 13)          // this frame's probe_visibility
GIB_CONST(uint, kIvBindRays, 14)                // probe_ray_radiance: vec4 (rgb, distance) per ray
GIB_CONST(uint, kIvBindFallback, 15)            // iv_fallback (this frame's): the probes whose rays missed the cache
GIB_CONST(uint, kIvBindNextFallback, 16)        // iv_fallback (last frame's copy): reset for the next frame
GIB_CONST(uint, kIvSpecCacheFallback, 0)        // 1: hits without a shaded cell use last frame's volumes
GIB_CONST(uint, kIvSpecAlpha, 1)                // 1: the scene has alpha-tested materials (probe rays test them)
GIB_CONST(uint, kIvSpecDither, 2)               // 1: the atlas store rounds stochastically (option dither_stores)
GIB_CONST(uint, kIvSpecRays, 3)                 // irradiance_volume_probe.comp: rays_per_probe (group-shared array size)
GIB_CONST(uint, kIvSpecPass, 4)                 // irradiance_volume_probe.comp: kIvPass* below
// The probe kernel's passes. kIvPassAll: every probe, a ray whose hit has no shaded cell takes the
// cache fallback inline. kIvPassCached: every probe, without the fallback's code; a probe with such
// a ray writes nothing and is listed in iv_fallback instead. kIvPassFallback: the listed probes, with
// the fallback (an indirect dispatch of as many groups; none in a steady frame).
GIB_CONST(uint, kIvPassAll, 0)
GIB_CONST(uint, kIvPassCached, 1)
GIB_CONST(uint, kIvPassFallback, 2)
// iv_fallback (uint words): VkDispatchIndirectCommand (x = listed probes, y = z = 1), a pad
// word, then the listed probe indices.
GIB_CONST(uint, kIvFallbackListFirst, 4)
// Exponent k of the max(0, n.d)^k weight of the distance moments.
GIB_CONST(float, kIvDistanceSharpness, 16.0)
struct IvPush {
  RcParams rc;
  uvec4 extra;  // x: the cascade irradiance_volume_probe.comp carries from last frame's copy (kIvNoCarry: none)
};
GIB_CONST(uint, kIvNoCarry, 0xffffffffu)
// irradiance_volume_carry.comp: the rows of cascade `cascade` are copied from last frame.
struct IvCarryPush {
  uint cascade;  // the cascade whose atlas rows are copied from last frame's copy
  uint pad0, pad1, pad2;
};
GIB_SHARED_END
#endif
