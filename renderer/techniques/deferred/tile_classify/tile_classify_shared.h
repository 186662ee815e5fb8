#ifndef GIB_TILE_CLASSIFY_SHARED_H
#define GIB_TILE_CLASSIFY_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kTileMaskGroup, 8)  // mask kernel: 8x8 pixels per workgroup
GIB_CONST(uint, kTileScanSize, 256) // args kernel: one workgroup
GIB_CONST(uint, kTileBindPosition, 8)
GIB_CONST(uint, kTileBindEmissive, 9)
GIB_CONST(uint, kTileBindWorkloads, 10)  // tile_workloads (layout: deferred_shared.h)
GIB_CONST(uint, kTileBindVbuffer, 11)    // vbuffer: the pixel's material (cloth)
GIB_CONST(uint, kTileBindNormal, 12)     // gbuffer_normal: decals fade with it
struct TilePush {
  uint tiles_x;
  uint tiles;
  uint pad0, pad1;
};
GIB_SHARED_END
#endif
