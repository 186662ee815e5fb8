#version 460
#extension GL_GOOGLE_include_directive : require
// gi_composite with the history stored as r11g11b10f (history_format 2); the kernel is gi_composite.glsl.
#define GI_HISTORY_FORMAT 2
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite.glsl"
