#version 460
#extension GL_GOOGLE_include_directive : require
// gi_upscale with its history stored as rgba16f (history_format 1); the kernel is gi_upscale.glsl.
#define GI_HISTORY_FORMAT 1
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale.glsl"
