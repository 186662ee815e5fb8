#ifndef GIB_GBUFFER_UPDATE_SHARED_H
#define GIB_GBUFFER_UPDATE_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kUpdateBindVbuffer, 8)
GIB_CONST(uint, kUpdateBindPosition, 9)
GIB_CONST(uint, kUpdateBindNormal, 10)
GIB_CONST(uint, kUpdateBindAlbedo, 11)     // rgba16f, read and written (rgb only where a decal covers)
GIB_CONST(uint, kUpdateBindWorkloads, 12)  // tile_workloads (classified kernels)
GIB_CONST(uint, kUpdateBindRates, 13)      // vrcs_rates (VRCS kernels)
GIB_CONST(uint, kUpdateGroup, 8)           // 8x8 workgroups: 16 per listed 32x32 tile, one per rate tile
struct UpdatePush {
  uint tiles_x;
  uint tiles;
  uint rate_tiles_x;  // VRCS: 8x8 rate tiles per row
  uint pad0;
};
GIB_SHARED_END
#endif
