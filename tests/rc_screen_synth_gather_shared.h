// Test-only kernel of tests/test_radiance_cache_screen.cpp: synthetic final-gather output.
#ifndef GIB_RC_SCREEN_SYNTH_GATHER_SHARED_H
#define GIB_RC_SCREEN_SYNTH_GATHER_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kSynthGroup, 8)
GIB_CONST(uint, kSynthBindPosition, 0)  // gbuffer_position
GIB_CONST(uint, kSynthBindShR, 1)
GIB_CONST(uint, kSynthBindShG, 2)
GIB_CONST(uint, kSynthBindShB, 3)
GIB_CONST(uint, kSynthBindHit, 4)
GIB_CONST(uint, kSynthBindDirect, 5)  // gather_direct: rgb = the same value as L0
struct SynthPush {
  uint divisor;
  float split_y;      // gather pixels whose surface lies above this height get `high`
  float low, high;    // L0 of every channel; +-noise added per pixel
  float noise;
  uint nan_every;     // > 0: every nan_every-th surface gather pixel (g.x + 7 g.y) gets a NaN in SH r's L1 x
  uint pad1, pad2;
};
GIB_SHARED_END
#endif
