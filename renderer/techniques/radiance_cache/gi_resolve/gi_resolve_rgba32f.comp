#version 460
#extension GL_GOOGLE_include_directive : require
// gi_resolve with the history stored as rgba32f (history_format 3); the kernel is gi_resolve.glsl.
#define GI_HISTORY_FORMAT 3
#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve.glsl"
