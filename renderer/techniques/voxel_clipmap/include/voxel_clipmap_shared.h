// The voxel-clipmap technique's cross-pass contract (C++ and GLSL): the parameters every pass
// receives in its push constants, the clipmap state, the irradiance queue and the layout of the
// voxel and ambient-cube buffers. Passes never include each other's headers; what two passes
// must agree on lives here. Design: renderer/techniques/voxel_clipmap/voxel_clipmap.md.
#ifndef GIB_VOXEL_CLIPMAP_SHARED_H
#define GIB_VOXEL_CLIPMAP_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN

GIB_CONST(uint, kVcMaxLevels, 8)
GIB_CONST(uint, kVcMaxRays, 256)  // rays per irradiance cell: one thread each, one workgroup per cell

// Scene voxels (buffer scene_voxel_data): level l holds N^3 voxels of size voxel_size x 2^l,
// voxel (world grid coordinate g) at slot g mod N (toroidal), index l N^3 + (s.z N + s.y) N + s.x.
// A voxel is a uvec4: x reflected radiance RGB9E5 (outgoing, lit, without emission), y opacity
// unorm8 (bits 0-7) | flags (bits 8-12) | the low bits of the second triangle (bits 13-31), z
// emitted radiance RGB9E5, w the triangle scene_voxel_light lights it from (scene_voxel_fill's
// key, kVcFillTriangleMask bits: triangle + 1; 0: none) | the second triangle's high bits (bits
// 23-26). The fill keeps the best triangle of each dominant normal axis (x, y, z): the first
// is the best of all, the second (+ 1; 0: none; vc_second_triangle) the best of the two other
// axes, the third the remaining axis' (buffer scene_voxel_third: uint per voxel, triangle + 1,
// 0: none). Where walls meet a floor or ceiling one voxel holds up to three surfaces, and the
// cube lookups' wall test needs every plane.
GIB_CONST(uint, kVcOpacityMask, 0xff)
GIB_CONST(uint, kVcVoxelFed, 0x100)       // lit from the G-buffer at least once (else: written without averaging)
GIB_CONST(uint, kVcVoxelGeometry, 0x200)  // opacity from voxelising scene triangles (scene_voxel_fill)
GIB_CONST(uint, kVcVoxelNew, 0x400)       // entered the clipmap (or was invalidated) this frame
GIB_CONST(uint, kVcVoxelOpaqueFed, 0x800) // an opaque pixel fed it: semi-transparent pixels keep its opacity
GIB_CONST(uint, kVcVoxelLit, 0x1000)      // lit from its triangle at least once (scene_voxel_light)
GIB_CONST(uint, kVcSecondLowShift, 13)     // second triangle + 1: bits 0-18 in y bits 13-31,
GIB_CONST(uint, kVcSecondLowBits, 19)      // bits 19-22 in w bits 23-26
GIB_CONST(uint, kVcSecondHighShift, 23)
GIB_CONST(uint, kVcSecondHighMask, 0x7800000)

// scene_voxel_fill's per-voxel key, merged with atomicMax: opacity byte (bits 24-31), whether the
// triangle faces the camera (bit 23), triangle + 1 (bits 0-22; 0 past 2^23 - 2 triangles). The
// largest opacity wins, then a triangle facing the camera (the side rays from the viewer's cells
// meet), then the largest triangle id (a fixed choice, whatever the thread order).
GIB_CONST(uint, kVcFillFacing, 0x800000)
GIB_CONST(uint, kVcFillTriangleMask, 0x7fffff)

// Irradiance cells (buffers irradiance_x / _y / _z, irradiance_cell_state): level l holds M^3
// cells, M = N / 2, of size 2 x voxel size; toroidal like the voxels. Each axis buffer holds
// the +/- pair of that axis' ambient-cube directions as 14 floats per cell: bounce (light
// voxels reflect) towards +axis rgb, towards -axis rgb, then direct (sky through ray misses,
// emission of the voxels hit) towards +axis rgb, -axis rgb, then the hit share towards +axis,
// -axis (the cosine-weighted share of the rays that met voxels: 1 - transmittance). Colour
// values are the cosine-weighted mean incoming radiance around the direction (irradiance / pi),
// so a surface facing +axis reflects albedo x value.
GIB_CONST(uint, kVcCellFloats, 14)
// irradiance_cell_state: uint per cell: age in frames (bits 0-15, saturating), flags.
GIB_CONST(uint, kVcAgeMask, 0xffff)
GIB_CONST(uint, kVcCellUpdated, 0x10000)    // holds irradiance (relit, or inherited from the coarser level)
GIB_CONST(uint, kVcCellGeometry, 0x20000)   // its box holds voxels with opacity (queue A / A')
GIB_CONST(uint, kVcCellVisible, 0x40000)    // in the view frustum this frame
GIB_CONST(uint, kVcCellRelit, 0x80000)      // relit at least once (else: queue A' when it has geometry)
// Relit with every voxel of its 2 x 2 x 2 opaque: its rays started inside geometry (a cell within a
// wall or roof, whose first voxel may be the sunlit outer face); the cube lookups give it no weight.
GIB_CONST(uint, kVcCellSolid, 0x100000)
// Which of its 2 x 2 x 2 voxels the last relight's rays started in (bit 0: +x, 1: +y, 2: +z):
// the cube lookups' wall test ends its segment there (vc_cell_ray_origin).
GIB_CONST(uint, kVcCellOriginShift, 21)
GIB_CONST(uint, kVcCellOriginMask, 0xe00000)
// Relit with no empty voxel but some semi-transparent (foliage): its rays started at its centre.
GIB_CONST(uint, kVcCellOriginCentre, 0x1000000)

// irradiance_cell_vis: per cell kVcCellVisWords uints, the cube lookups' wall test (wall_test 2,
// vc_cell_sees). The relight floods the voxels without geometry (kVcVoxelGeometry clear)
// 6-connected from the voxel its rays start in, over a window of kVcVisWindow^3 voxels (world
// voxels 2k - 3 .. 2k + 4 of cell k), and stores the reached voxels of the window's middle
// kVcVisSpan^3 (2k - 2 .. 2k + 3: every voxel a lookup of this cell can ask about), bit
// (z x 6 + y) x 6 + x of the middle's local coordinates, 32 a word, lowest bit first.
GIB_CONST(int, kVcVisWindow, 8)
GIB_CONST(int, kVcVisSpan, 6)
GIB_CONST(uint, kVcCellVisWords, 7)
// Flood steps: each spreads along x through a row's free voxels and one voxel across rows (y, z);
// 24 reach every row of the window by a path that goes around a wall (14 rows corner to corner).
GIB_CONST(uint, kVcVisSteps, 24)

// Flags in VcParams.grid.w.
GIB_CONST(uint, kVcFlagNanGuards, 1)
GIB_CONST(uint, kVcFlagConvexOffset, 2)
GIB_CONST(uint, kVcFlagGeometryFill, 4)
GIB_CONST(uint, kVcFlagSemiTransparent, 8)
GIB_CONST(uint, kVcFlagSkyFromCubes, 16)   // direct_lighting traces no sky rays: the cubes' direct part (sky, emitters) lights pixels
GIB_CONST(uint, kVcFlagInvalidate, 32)
GIB_CONST(uint, kVcFlagMultiBounce, 64)    // the feed adds albedo x the clipmap's bounce (0: one bounce, a control)
GIB_CONST(uint, kVcFlagSelectPerQueue, 128)  // irradiance_select keeps one P for cells with geometry, one for empty cells
GIB_CONST(uint, kVcFlagGeometryLight, 256)   // scene_voxel_light lights voxels no pixel fed from their triangle
// direct_lighting traced sky rays per pixel (traced mode, a sky or emitters in the scene):
// direct_light's alpha is each pixel's share of rays that met a surface, and the pixel's bounce
// is gathered over that share only (vc_bounce_for_pixel).
GIB_CONST(uint, kVcFlagPixelSkyHits, 512)
// The cube lookups' wall test (with geometry_light): wall_test 1, a voxel walk from the pixel to
// the cell's ray origin through the triangles' planes (vc_cell_behind_wall); wall_test 2, one bit
// of the cell's flood mask (irradiance_cell_vis). Neither flag: no wall test.
GIB_CONST(uint, kVcFlagWallWalk, 1024)
GIB_CONST(uint, kVcFlagWallFlood, 2048)

struct VcParams {
  uvec4 grid;    // x: N voxels per axis per level, y: levels, z: frame, w: kVcFlag*
  vec4 sizes;    // x: level-0 voxel size (m), y: feed weight (exponential average), z: relight history frames, w: unused
  uvec4 budget;  // x: feed pixels per frame (K), y: queue A capacity, z: queue A' capacity, w: queue B capacity
  uvec4 rays;    // x: rays per cell, y: max march steps, z: seed, w: voxels scene_voxel_light visits per frame
};

// Per level origins: the minimum-corner world grid coordinate of the level's box (voxels or
// cells); w: bit 0 valid, bit 1 cells entered this frame.
struct VcState {
  ivec4 voxel_origin[kVcMaxLevels];
  ivec4 voxel_prev[kVcMaxLevels];
  ivec4 cell_origin[kVcMaxLevels];
  ivec4 cell_prev[kVcMaxLevels];
  vec4 select;   // x: threshold P of age x random > P (cells with geometry under select_per_queue), y: candidates that passed last frame, z: P of empty cells (select_per_queue), w: unused
  uvec4 stats;   // x: voxels entered (moved in or invalidated), y: voxels fed, z: voxels given geometry opacity, w: cells entered
};
GIB_CONST(uint, kVcOriginValid, 1)
GIB_CONST(uint, kVcOriginEntered, 2)

// irradiance_queue: header, then entries (cell index), capacity A' + A + B.
struct VcQueue {
  uvec4 args;    // VkDispatchIndirectCommand: x cells to relight, 1, 1; w unused
  uvec4 counts;  // x: queue A' taken, y: queue A taken, z: queue B taken, w: candidates that passed
};

GIB_SHARED_END

#ifndef __cplusplus
// The buffers as GLSL declares them (vc_common.glsl reads them by these names).
#define VC_STATE_BUFFER(B, QUAL) \
  layout(std430, set = 0, binding = (B)) QUAL buffer VcStateBuffer { VcState vc_state; };
#define VC_VOXEL_BUFFER(B, QUAL) \
  layout(std430, set = 0, binding = (B)) QUAL buffer VcVoxelBuffer { uvec4 vc_voxels[]; };
#define VC_THIRD_BUFFER(B, QUAL) \
  layout(std430, set = 0, binding = (B)) QUAL buffer VcThirdBuffer { uint vc_voxel_third[]; };
#define VC_VIS_BUFFER(B, QUAL) \
  layout(std430, set = 0, binding = (B)) QUAL buffer VcCellVisBuffer { uint vc_cell_vis[]; };
#define VC_CUBE_BUFFERS(BX, BY, BZ, BS, QUAL)                                              \
  layout(std430, set = 0, binding = (BX)) QUAL buffer VcCubeX { float vc_cube_x[]; };      \
  layout(std430, set = 0, binding = (BY)) QUAL buffer VcCubeY { float vc_cube_y[]; };      \
  layout(std430, set = 0, binding = (BZ)) QUAL buffer VcCubeZ { float vc_cube_z[]; };      \
  layout(std430, set = 0, binding = (BS)) QUAL buffer VcCellState { uint vc_cell_state[]; };
#endif
#endif
