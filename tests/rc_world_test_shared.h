// tests/test_radiance_cache_world.cpp <-> rc_world_test.comp: a probe kernel that exposes what
// the radiance-cache world passes compute (hit positions and cache keys, decoded atlas texels).
#ifndef GIB_RC_WORLD_TEST_SHARED_H
#define GIB_RC_WORLD_TEST_SHARED_H
#include "frame_shared.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kRcTestGroup, 64)
GIB_CONST(uint, kRcTestBindHits, 8)
GIB_CONST(uint, kRcTestBindKeys, 9)
GIB_CONST(uint, kRcTestBindIrradiance, 10)
GIB_CONST(uint, kRcTestBindVisibility, 11)
GIB_CONST(uint, kRcTestBindDecoded, 12)
GIB_CONST(uint, kRcTestSpecMode, 0)  // 0: hit keys, 1: decode the atlas
struct RcTestKey {
  vec4 position;  // xyz: hit position as radiance_cache_update computes it; w: LOD
  uvec4 key;      // x: rc_cell_key (0: miss or inside), y: first slot, z: side (rc_side), w: ProbeHit.key as stored
};
GIB_SHARED_END
#endif
