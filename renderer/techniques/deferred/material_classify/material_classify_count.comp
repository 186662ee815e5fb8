#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/material_classify/material_classify_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)

layout(local_size_x = kMatClassifyGroup, local_size_y = kMatClassifyGroup) in;
layout(set = 0, binding = kMatBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(std430, set = 0, binding = kMatBindSegments) buffer Segments { uint seg[]; };
layout(push_constant) uniform Push { MatClassifyPush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(vbuffer)))) return;
  uvec2 ids = imageLoad(vbuffer, p).xy;
  if (ids.x == kVisibilityNone) return;
  uint tile = uint(p.x >> kDeferredTileShift) + uint(p.y >> kDeferredTileShift) * push.tiles_x;
  uint material = gib_instances[ids.y].material;
  atomicAdd(seg[kSegHeader + tile * push.materials + material], 1u);
}
