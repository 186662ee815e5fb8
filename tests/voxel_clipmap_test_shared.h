// tests/voxel_clipmap_test.comp <-> tests/test_voxel_clipmap.cpp.
#ifndef GIB_VOXEL_CLIPMAP_TEST_SHARED_H
#define GIB_VOXEL_CLIPMAP_TEST_SHARED_H
#include "gib_shared.h"
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kVcTestGroup, 64)
GIB_CONST(uint, kVcTestBindState, 0)
GIB_CONST(uint, kVcTestBindX, 1)
GIB_CONST(uint, kVcTestBindY, 2)
GIB_CONST(uint, kVcTestBindZ, 3)
GIB_CONST(uint, kVcTestBindCells, 4)
GIB_CONST(uint, kVcTestBindIn, 5)
GIB_CONST(uint, kVcTestBindOut, 6)
GIB_CONST(uint, kVcTestAddressing, 0)  // in.a: g xyz, level; in.p0: origin xyz (int bits), slot index
GIB_CONST(uint, kVcTestLevel, 1)       // in.p0: point xyz
GIB_CONST(uint, kVcTestCube, 2)        // in.a.x: cell, in.p0: normal
GIB_CONST(uint, kVcTestOverlap, 3)     // in.p0-p2: triangle, in.p3: box centre xyz, half extent w
GIB_CONST(uint, kVcTestOpacity, 4)     // in.p0.w: opacity
GIB_CONST(uint, kVcTestFillKey, 5)     // in.a: opacity byte, facing, triangle
GIB_CONST(uint, kVcTestClosest, 6)     // in.p0-p2: triangle, in.p3: point
GIB_CONST(uint, kVcTestSecond, 7)      // in.a: voxel y, w, second triangle + 1 to set
GIB_CONST(uint, kVcTestVisStep, 8)     // in.a: free row, seed, row, beside; in.p0.xy: seed box x lo, hi (int bits)
GIB_CONST(uint, kVcTestVisBit, 9)      // in.a.xyz: voxel g; in.p0.xyz: cell k (int bits)
struct VcTestIn {
  ivec4 a;
  vec4 p0, p1, p2, p3;
};
struct VcTestOut {
  uvec4 u;
  ivec4 i;
  vec4 f0, f1;
};
struct VcTestPush {
  VcParams vc;
  uvec4 mode;  // x: mode, y: count
};
GIB_SHARED_END
#endif
