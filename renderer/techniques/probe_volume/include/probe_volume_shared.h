// The probe-volume technique's cross-pass contract (C++ and GLSL): the parameters every pass
// receives in its push constants, the per-probe state, the selection list and the layout of
// the probe buffers. Passes never include each other's headers; what two passes must agree on
// lives here. Design: renderer/techniques/probe_volume/probe_volume.md.
#ifndef GIB_PROBE_VOLUME_SHARED_H
#define GIB_PROBE_VOLUME_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN

GIB_CONST(uint, kPvMaxCascades, 8)
// Octahedral tiles per probe (AC Shadows "Probe data buffers"): the G-buffer 20x20 texels
// (no border), radiance and visibility 10x10 + 1-texel border, irradiance 5x5 + border.
GIB_CONST(uint, kPvGbufferSide, 20)
GIB_CONST(uint, kPvGbufferTexels, 400)
GIB_CONST(uint, kPvRadianceInterior, 10)
GIB_CONST(uint, kPvRadianceSide, 12)
GIB_CONST(uint, kPvRadianceTexels, 144)
GIB_CONST(uint, kPvIrradianceInterior, 5)
GIB_CONST(uint, kPvIrradianceSide, 7)
GIB_CONST(uint, kPvIrradianceTexels, 49)
// A G-buffer texel whose ray missed stores this half-float depth (+Inf).
GIB_CONST(uint, kPvMissDepthBits, 0x7c00)
// A stored depth (a half float: 11 significant bits, rounded to nearest) is within depth x 2^-11
// of the hit. Points rebuilt from it are pulled back along the ray by depth x 2^-10, so they stay
// in front of the surface and their shadow rays do not start behind it (with the exact depth
// about half the far texels shadowed themselves from local lights: interior-point-light).
GIB_CONST(float, kPvDepthPullback, 1.0 / 1024.0)

// Per-probe buffers, probe index p = cascade * probes_per_cascade + slot (toroidal: slot
// x + X * (z + Z * y) of the cell's grid coordinate modulo the grid, so a probe keeps its slot
// while the volume scrolls):
//   probe_gb_material  uvec2 per G-buffer texel: albedo rgb unorm8 + translucency unorm8,
//                      emission RGB9E5                                            (8 bytes)
//   probe_gb_normal    uint per texel: octahedral normal 12+12 bits (the side the ray hit),
//                      sun visibility unorm8                                       (4 bytes)
//   probe_gb_depth     uint per two texels: hit distance as half floats (miss: +Inf) (2 bytes)
//   probe_irradiance   uvec2 per tile texel: half4 (rgb irradiance / pi x scale, a unused)
//   probe_radiance     uvec2 per tile texel: half4 (rgb reflected radiance x scale, a sky visibility)
//   probe_visibility   uint per two tile texels: unorm8 mean depth, unorm8 mean depth^2, depth
//                      in units of spacing * sqrt(3), clamped to [0, 1] before averaging
// 14 bytes per G-buffer texel as the seed's table.

// Probe flags (PvProbe.coord.w).
GIB_CONST(uint, kPvProbeTraced, 1)     // the G-buffer holds this slot's current cell
GIB_CONST(uint, kPvProbeValid, 2)      // lit and convolved: samplers may use it
GIB_CONST(uint, kPvProbeDisabled, 4)   // inside geometry and could not move: samplers skip it
GIB_CONST(uint, kPvProbeIndoor, 8)     // inside an indoor volume (probe_classify)
GIB_CONST(uint, kPvProbeQuarter, 16)   // last traced at quarter resolution
GIB_CONST(uint, kPvProbeRetrace, 32)   // probe_relocate chose a new offset (pending): traced there first among the G-buffer refreshes

struct PvProbe {
  ivec4 coord;     // xyz: the world grid cell whose data the slot holds; w: kPvProbe* flags
  vec4 offset;     // xyz: relocation offset (m), w: lighting scale (stored lighting = true x scale)
  vec4 meta;       // x: sky visibility, y: sun + sky estimate (luminance) at the last relight,
                   // z: local-light luminance (mean over texels), w: mean luminance
  vec4 geometry;   // x: back faces within reach / hits, y: min depth, z: max depth (m), w: texel of max depth
  uvec4 stamp;     // x: frame + 1 when last selected, y: class then (kPvClass*), z: frame + 1 when last traced, w: unused
  vec4 pending;    // xyz: the offset probe_relocate chose, taken at the next trace (kPvProbeRetrace); w: unused
};
struct PvCascade {
  ivec4 origin;  // xyz: grid cell of the volume's minimum corner this frame
  uvec4 rr;      // x: next G-buffer refresh slot, y: next relight slot, z: new probes this frame, w: 1 for the run's cascades
};
// probe_state: kPvMaxCascades PvCascade, then one PvProbe per probe.

GIB_CONST(uint, kPvClassNew, 0)       // entered the volume: full update (quarter resolution)
GIB_CONST(uint, kPvClassGbuffer, 1)   // round robin: G-buffer re-traced at full resolution
GIB_CONST(uint, kPvClassRelight, 2)   // round robin: lighting and convolution only

// probe_selection: this header, then probe_budget probe indices (new, then G-buffer, then relight).
struct PvSelection {
  uvec4 traced_args;  // indirect dispatch over traced probes: (new + gbuffer, 1, 1), w: unused
  uvec4 all_args;     // indirect dispatch over all selected: (new + gbuffer + relight, 1, 1), w: unused
  uvec4 counts;       // x: new, y: G-buffer refresh, z: relight only, w: new probes left for later frames
};
// probe_texel_lists (probe_relight): this header, then the hit list (probe_budget x 400
// entries), then the miss list; an entry is selection index << 9 | texel.
struct PvTexelLists {
  uvec4 hit_args;   // indirect: (ceil(hit texels / 64), 1, 1), w: hit texels
  uvec4 miss_args;  // indirect: (ceil(miss texels / 64), 1, 1), w: miss texels
};

// pixel_hits (world_trace -> hit_lighting), rgba32ui per ray pixel: x albedo rgb + translucency
// unorm8, y the hit normal (oct 16+16, the side the ray sees), z hit distance (float bits; the
// range on a miss), w flags:
GIB_CONST(uint, kPvPixelValid, 1)   // the source pixel is a surface (not sky)
GIB_CONST(uint, kPvPixelHit, 2)     // the ray hit within its range
GIB_CONST(uint, kPvPixelBack, 4)    // the ray left through the back of a translucent surface
GIB_CONST(uint, kPvPixelWorld, 8)   // screen_trace could not settle it: world_trace traces it from z (start distance)
GIB_CONST(uint, kPvPixelScreen, 16) // settled on screen (hit: material from the G-buffer at the hit pixel)
// pixel_trace_stats (screen_trace, world_trace): uvec4 (valid ray pixels, screen hits, screen misses, world rays).

// Flags (PvParams.flags.x).
GIB_CONST(uint, kPvFlagNanGuards, 1)
GIB_CONST(uint, kPvFlagMultiBounce, 2)
GIB_CONST(uint, kPvFlagLightingScale, 4)
GIB_CONST(uint, kPvFlagVisibility, 8)
GIB_CONST(uint, kPvFlagInverseRay, 16)
GIB_CONST(uint, kPvFlagProbeAo, 32)
GIB_CONST(uint, kPvFlagRelocation, 64)
GIB_CONST(uint, kPvFlagMaterialMask, 128)
GIB_CONST(uint, kPvFlagTranslucentRays, 256)
GIB_CONST(uint, kPvFlagQuarterNew, 512)
GIB_CONST(uint, kPvFlagIndoor, 1024)   // indoor / outdoor classes (Scene::indoor_volumes)
GIB_CONST(uint, kPvFlagLookupView, 2048)  // diagnostic: the probes' irradiance at the pixel's own surface

// Push constants shared by the probe-volume passes (80 bytes); a pass may append its own.
struct PvParams {
  uvec4 grid;      // x: probes along x and z, y: along y, z: cascades, w: frame
  vec4 volume;     // x: cascade-0 spacing (m), y: forward offset (share of the width), z: probe trace range
                   //    (spacings), w: per-pixel range (x the probe trace range)
  vec4 sampling;   // x: normal offset, y: view offset (spacings), z: nearest-probe weight, w: G-buffer share
  uvec4 flags;     // x: kPvFlag* bits, y: probe budget, z: pixel divisor, w: denoise radius | history n_max << 16
  vec4 pixel;      // x: per-pixel rays' minimum start distance (m), y-w: unused
};

GIB_SHARED_END
#endif
