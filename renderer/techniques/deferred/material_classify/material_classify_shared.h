#ifndef GIB_MATERIAL_CLASSIFY_SHARED_H
#define GIB_MATERIAL_CLASSIFY_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kMatClassifyGroup, 8)    // count: 8x8 pixels per workgroup
GIB_CONST(uint, kMatScanSize, 256)       // scan and write: 256 invocations
GIB_CONST(uint, kMatBindVbuffer, 8)
GIB_CONST(uint, kMatBindSegments, 9)     // material_segments (layout: deferred_shared.h)
GIB_CONST(uint, kMatBindCommands, 10)    // pixel_commands: padded pixel lists
struct MatClassifyPush {
  uint materials;  // scene materials (M)
  uint tiles_x;
  uint tiles;      // T
  uint pad;
};
GIB_SHARED_END
#endif
