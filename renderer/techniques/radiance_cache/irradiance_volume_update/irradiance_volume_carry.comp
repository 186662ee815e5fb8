#version 460
// The split path's carry (CPU devices; the GPU kernel irradiance_volume_probe.comp carries inside
// its own dispatch). Carries the atlas rows of one cascade, the one updated last frame, from last frame's copy into
// this frame's. The atlas ping-pongs between two copies, one written each frame: this frame's
// copy holds the state of two frames ago, which differs from last frame's only in the cascade
// last frame updated. Every other cascade already matches; the cascade updated this frame is
// rewritten whole by the update kernel after this (irradiance_volume_update.cpp).
// A compute copy instead of vkCmdCopyImage of the whole atlas: lavapipe's image copy of the
// 2560 x 160*cascades atlas cost ~300 ms per frame; this skips the rewritten rows too.
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update_shared.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = kIvBindPrevIrradiance, r32ui) uniform readonly uimage2D prev_irradiance;
layout(set = 0, binding = kIvBindPrevVisibility, rg16f) uniform readonly image2D prev_visibility;
layout(set = 0, binding = kIvBindIrradiance, r32ui) uniform writeonly uimage2D out_irradiance;
layout(set = 0, binding = kIvBindVisibility, rg16f) uniform writeonly image2D out_visibility;
layout(push_constant) uniform Push { IvCarryPush carry; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, int(carry.cascade * kProbeAtlasRowsPerCascade));
  ivec2 size = imageSize(out_irradiance);
  if (p.x >= size.x || p.y >= size.y || gl_GlobalInvocationID.y >= kProbeAtlasRowsPerCascade) return;
  imageStore(out_irradiance, p, imageLoad(prev_irradiance, p));
  imageStore(out_visibility, p, imageLoad(prev_visibility, p));
}
