#version 460
#extension GL_GOOGLE_include_directive : require
// direct_lighting with the sun's visibility read from a slot (DirectLightingParams::sun_visibility).
#define GIB_DIRECT_SUN_VISIBILITY
#include "renderer/passes/direct_lighting/direct_lighting_main.glsl"
