#version 460
#extension GL_GOOGLE_include_directive : require
// gi_composite with the history stored as rgb9e5 (history_format 0); the kernel is gi_composite.glsl.
#define GI_HISTORY_FORMAT 0
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite.glsl"
