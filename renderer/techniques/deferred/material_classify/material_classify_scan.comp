#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#define GIB_SCAN_SIZE kMatScanSize
#include "renderer/techniques/deferred/include/deferred_scan.glsl"

// One workgroup. Segments in the order shader, tile, material; each padded to kDeferredWave.
layout(local_size_x = kMatScanSize) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

uint shader_of(uint material) { return min(gib_materials[material].texture, kDeferredShaderCount - 1u); }

void main() {
  uint entries = push.tiles * push.materials;
  uint offsets = kSegHeader + entries;
  uint slot = 0u, pixels = 0u, segments = 0u;
  for (uint s = 0u; s < kDeferredShaderCount; ++s) {
    uint first = slot;
    for (uint base = 0u; base < entries; base += kMatScanSize) {
      uint e = base + gl_LocalInvocationIndex;
      uint count = e < entries && shader_of(e % push.materials) == s ? seg[kSegHeader + e] : 0u;
      uint padded = (count + kDeferredWave - 1u) / kDeferredWave * kDeferredWave;
      uint total, ctotal, ntotal;
      uint before = gib_workgroup_exclusive_scan(padded, total);
      gib_workgroup_exclusive_scan(count, ctotal);
      gib_workgroup_exclusive_scan(count > 0u ? 1u : 0u, ntotal);
      if (count > 0u) seg[offsets + e] = slot + before;
      slot += total;
      pixels += ctotal;
      segments += ntotal;
    }
    if (gl_LocalInvocationIndex == 0u) {
      seg[4u * s + 0u] = (slot - first) / kDeferredWave;
      seg[4u * s + 1u] = 1u;
      seg[4u * s + 2u] = 1u;
      seg[4u * s + 3u] = first / kDeferredWave;
    }
  }
  if (gl_LocalInvocationIndex == 0u) {
    seg[kSegStats + kStatPixels] = pixels;
    seg[kSegStats + kStatWaves] = slot / kDeferredWave;
    seg[kSegStats + kStatPaddingSlots] = slot - pixels;
    seg[kSegStats + kStatSegments] = segments;
  }
}
