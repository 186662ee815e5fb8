#ifndef GIB_SSDO_SSGI_SHARED_H
#define GIB_SSDO_SSGI_SHARED_H
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space_shared.h"
GIB_SHARED_BEGIN
GIB_CONST(uint, kSsCombinedBlock, 2)          // each thread shades a 2x2 pixel block
GIB_CONST(uint, kSsCombinedStream, 0x55c0u)   // hash stream: the quad's turn and each block's pixel and first step
GIB_CONST(uint, kSsSurfacesGroup, 8)          // ssdo_ssgi_surfaces: 8x8 blocks a workgroup
GIB_CONST(uint, kSsCombinedBindPosition, 8)   // gbuffer_position (rgba32f)
GIB_CONST(uint, kSsCombinedBindNormal, 9)     // gbuffer_normal (rgba16f)
GIB_CONST(uint, kSsCombinedBindAlbedo, 10)    // gbuffer_albedo (rgba16f)
GIB_CONST(uint, kSsCombinedBindEmissive, 11)  // gbuffer_emissive (rgba16f)
GIB_CONST(uint, kSsCombinedBindDirect, 12)    // direct_light (rgba32f)
GIB_CONST(uint, kSsCombinedBindLocalPrev, 13) // last frame's ssdo_local_light (rgba16f; ssgi_indirect's when absent)
GIB_CONST(uint, kSsCombinedBindLocal, 14)     // out: ssdo_local_light (rgba16f; ssgi_indirect when absent, unwritten)
GIB_CONST(uint, kSsCombinedBindCone, 15)      // out: ssdo_cone (rgba16f; ssgi_indirect when not asked for, unwritten)
// 16: unused (gow_direct is direct_aov's)
GIB_CONST(uint, kSsCombinedBindOutIndirect, 17)  // out: ssgi_indirect (rgba16f history; alpha: frames averaged)
GIB_CONST(uint, kSsCombinedBindOutRadiance, 18)  // out: gow_radiance
GIB_CONST(uint, kSsCombinedBindIndirectPrev, 19) // last frame's ssgi_indirect (its history, rgba16f)
GIB_CONST(uint, kSsCombinedBindSurfaces, 20)    // ss_surfaces (rg32ui, half size): each block's surface for the march
GIB_CONST(uint, kSsCombinedSpecLocal, 0)         // 1: the scene has unshadowed local lights
GIB_CONST(uint, kSsCombinedSpecDirections, 1)    // the direction set's size (sizes the shared direction table)
GIB_CONST(uint, kSsCombinedSpecCone, 2)          // 1: write ssdo_cone (option ss_cone, with local lights)
// The histories' frame count rides in ssgi_indirect's 16-bit alpha, exact up to 2048.
GIB_CONST(uint, kSsMaxHistory, 2048)
struct SsCombinedPush {
  vec4 radius;   // x: ssdo radius, y: ssgi radius, z: step length (m), w: unused
  vec4 thickness;  // x: ssdo thickness, y: ssgi thickness, z, w: unused
  uvec4 counts;  // x: directions, y: steps, z: bit 0 ssdo on, bit 1 ssgi on, w: 1 NaN guards
  uvec4 frame;   // x: 1 when last frame's images hold a frame, y: history frames (>= 1), z, w: unused
};
GIB_SHARED_END
#endif
