#ifndef GIB_MATERIAL_CLASSIFY_SHARED_H
#define GIB_MATERIAL_CLASSIFY_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kMatScanSize, 256)       // count, scan and write: 256 invocations
GIB_CONST(uint, kMatCountShared, 256)    // count: materials counted in group-shared memory
GIB_CONST(uint, kMatBindVbuffer, 8)
GIB_CONST(uint, kMatBindSegments, 9)     // material_segments (layout: deferred_shared.h)
GIB_CONST(uint, kMatBindCommands, 10)    // pixel_commands: padded pixel lists
GIB_CONST(uint, kMatBindBlocks, 11)      // material_scan_blocks: per (shader, block of kMatScanSize entries)
// material_scan_blocks, 4 words per (shader s, block b) at 4 (s * blocks + b): the block's padded
// slots, pixels and non-empty segments of shader s, then the block's first slot (the scan's).
GIB_CONST(uint, kMatBlockWords, 4)
struct MatClassifyPush {
  uint materials;  // scene materials (M)
  uint tiles_x;
  uint tiles;      // T
  uint blocks;     // ceil(T * M / kMatScanSize): the scan's blocks of entries
};
GIB_SHARED_END
#endif
