// The scan kernels' common head (material_classify_blocks, _scan, _offsets): bindings, the
// workgroup scan and one entry's padded size. Included after #version.
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#define GIB_SCAN_SIZE kMatScanSize
#define GIB_SCAN_UVEC3
#include "renderer/techniques/deferred/include/deferred_scan.glsl"

layout(local_size_x = kMatScanSize) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(std430, set = 0, binding = kMatBindBlocks) buffer Blocks { uint blk[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

uint shader_of(uint material) { return min(gib_materials[material].texture, kDeferredShaderCount - 1u); }

// Pixels of entry e (tile * materials + material) if its material is of shader s, else 0.
uint entry_count(uint e, uint s) {
  return e < push.tiles * push.materials && shader_of(e % push.materials) == s ? seg[kSegHeader + e] : 0u;
}
uint padded_size(uint count) { return (count + kDeferredWave - 1u) / kDeferredWave * kDeferredWave; }
uint block_word(uint s, uint b) { return kMatBlockWords * (s * push.blocks + b); }
