#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/shadow_maps/shadow_maps_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"

layout(location = 0) flat in uint in_instance;
layout(location = 1) in vec2 in_uv;
layout(location = 0) out float out_depth;

// The depth (0 nearest the sun) into a colour target the compute passes read as a storage
// image; alpha-tested materials cut out with the same mask as primary visibility.
void main() {
  GpuMaterial m = gib_materials[gib_instances[in_instance].material];
  if (m.alpha != GIB_ALPHA_NONE) {
    uint h = gib_pcg(gib_seed() ^ gib_pcg(gib_frame_index() ^ gib_pcg(uint(gl_FragCoord.x) ^ gib_pcg(uint(gl_FragCoord.y)))));
    if (gib_material_alpha(m, in_uv, h) < m.alpha_cutoff) discard;
  }
  out_depth = gl_FragCoord.z;
}
