// The radiance-cache technique's cross-pass contract (C++ and GLSL): the probe atlas layout,
// probe hit records, radiance-cache cells and counters, light-grid layout, and the parameters
// every radiance-cache pass receives in its push constants. Passes never include each other's
// headers; what two passes must agree on lives here. Design: renderer/techniques/radiance_cache/radiance_cache.md.
#ifndef GIB_RADIANCE_CACHE_SHARED_H
#define GIB_RADIANCE_CACHE_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN

// ---- irradiance volumes: cascades of 16^3 probes, camera-following, toroidal slots
GIB_CONST(uint, kProbeGridDim, 16)
GIB_CONST(uint, kMaxCascades, 8)
GIB_CONST(uint, kProbeTileInterior, 8)  // octahedral 8x8 texels per probe
GIB_CONST(uint, kProbeTileSize, 10)     // with a 1-texel border
// Atlas: probe (cascade c, slot x,y,z in 0..15) occupies the 10x10 tile whose top-left texel is
// ((z * 16 + x) * 10, (c * 16 + y) * 10). Width 2560 (the seed's), height cascades * 160.
// probe_irradiance: R32_UINT holding RGB9E5 irradiance / pi (what an albedo-1 surface reflects).
// probe_visibility: RG16F, mean and mean-squared distance to geometry around that direction.
GIB_CONST(uint, kProbeAtlasWidth, 2560)
GIB_CONST(uint, kProbeAtlasRowsPerCascade, 160)

// ---- probe rays: one record per (probe of the updated cascade, ray), 16 bytes
struct ProbeHit {
  uint triangle_plus1;  // 0: miss (sky)
  // The hit's cache-cell key (rc_cell_key of the hit point and the facing geometric normal), made
  // where the hit is found (the seed's trace "triggers the cache update"); 0 on a miss and on a
  // ray inside geometry (rc_probe_ray_inside), so a hit with key 0 is inside.
  uint key;
  uint barycentrics;    // unorm16 u | unorm16 v << 16
  float distance;       // metres along the ray (max distance on a miss)
};

// ---- world radiance cache: open-addressing hash table of cells, 16 bytes each
struct RcCell {
  uint key;           // 0: empty; else (hash(quantised position, lod) & ~3) | 1 (2, 3: insertion bid)
  uint radiance;      // RGB9E5 outgoing diffuse radiance of the cell
  uint shaded_frame;  // frame + 1 when last shaded (0: never)
  uint hit_index;     // ~(lowest id of its probe hit records) while queued this frame (shading
                      // input; radiance_cache_update sets it, radiance_cache_shade reads it and resets it to 0)
};
// Counters and the indirect dispatch for radiance_cache_shade (32 bytes, uvec4 aligned).
struct RcCounters {
  uint dispatch_x, dispatch_y, dispatch_z;  // indirect args: ceil(active_cells / 64), 1, 1
  uint active_cells;  // cells queued for shading this frame (== active list length; `active` is a GLSL reserved word)
  uint insertions;  // new cells
  uint collisions;  // linear-probing steps taken past an occupied cell
  uint drops;       // insertions that found no free cell within cache_max_probe steps
  uint reused;      // hits that found a cell shaded recently enough (not re-queued)
};
GIB_CONST(uint, kRcShadeGroup, 64)

// ---- light grid: cascades of 16^3 cells; cascade c spans light_grid_extent * 2^c metres,
// centred on the camera snapped to the cell size; each cell: count, then up to 64 light ids.
GIB_CONST(uint, kLightGridDim, 16)
GIB_CONST(uint, kLightGridMaxLights, 64)
GIB_CONST(uint, kLightGridCellWords, 65)

// Push constants shared by the radiance-cache passes (80 bytes); a pass may append its own.
struct RcParams {
  vec4 grid;    // x: cascade-0 probe spacing (m), y: cascades, z: rays per probe, w: cascade updated this frame
  vec4 cache;   // x: cell size (m), y: LOD distance (m), z: log2 cells, w: max probe steps
  vec4 bias;    // x: normal bias (m), y: view bias (m), z: visibility test (0/1), w: probe hysteresis
  uvec4 misc;   // x: frame, y: cache reuse frames, z: gather divisor, w: light-grid cascades
  uvec4 flags;  // x: leak mitigations kRcFlagSideKey | kRcFlagInsideTest, y: NaN guards (Settings::nan_guards),
                //    z: multi-bounce (RadianceCacheSettings::multi_bounce), w: probe rays (leak mitigation:
                //    a shadow ray from the sampled point to each probe; blocked probes get no weight)
};
// RcParams.flags.x bits. Side key: cache cells keyed by the surface side, so the two faces of a
// thin wall differ. Inside test: probe rays from inside geometry (the back of a solid, a surface
// nearer than kRcOnSurface spacings) mark their probe inside and insert no cell; bounce rays that
// meet the back of a solid bring nothing (radiance_cache.glsl rc_probe_ray_inside).
GIB_CONST(uint, kRcFlagSideKey, 1)
GIB_CONST(uint, kRcFlagInsideTest, 2)
struct LightGridParams {
  vec4 extent;  // x: cascade-0 extent (m), y: cascades, z: light count, w: unused
};

GIB_SHARED_END
#endif
