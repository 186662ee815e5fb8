#ifndef GIB_DEFERRED_TEXTURING_SHARED_H
#define GIB_DEFERRED_TEXTURING_SHARED_H
#include "frame_shared.h"
#include "vbuffer_shared.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kTexBindVbuffer, 8)
GIB_CONST(uint, kTexBindBary, 9)
GIB_CONST(uint, kTexBindBaryDeriv, 10)
GIB_CONST(uint, kTexBindTangentFrame, 11)
GIB_CONST(uint, kTexBindAlbedo, 12)    // G-buffer as the shared gbuffer pass writes it (gbuffer_shared.h)
GIB_CONST(uint, kTexBindNormal, 13)
GIB_CONST(uint, kTexBindPosition, 14)
GIB_CONST(uint, kTexBindEmissive, 15)
GIB_CONST(uint, kTexBindSegments, 16)  // material_segments: first waves, statistics
GIB_CONST(uint, kTexBindCommands, 17)  // pixel_commands
GIB_CONST(uint, kTexBindRates, 18)     // vrcs_rates (VRCS kernels)
// Specialization constants.
GIB_CONST(uint, kTexSpecShader, 0)       // 0..kDeferredShaderCount-1: the shader whose pixel lists run
GIB_CONST(uint, kTexSpecPermutation, 1)  // kTexPerm*
GIB_CONST(uint, kTexSpecHasUniform, 2)   // divergent permutation: the uniform one runs too
GIB_CONST(uint, kTexPermPlain, 0)        // no subgroup operations (devices without vote/ballot)
GIB_CONST(uint, kTexPermUniform, 1)      // instance data uniform across the subgroup, else early out
GIB_CONST(uint, kTexPermDivergent, 2)
struct TexPush {
  uint tiles_x;
  uint nan_guards;
  uint inject_nan;  // 1: NaN normal at (inject_x, inject_y) this frame (debug target 1)
  uint inject_x, inject_y;
  uint rate_tiles_x;  // VRCS: 8x8 rate tiles per row
  uint pad1, pad2;
};
GIB_SHARED_END
#endif
